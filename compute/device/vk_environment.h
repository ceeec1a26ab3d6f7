#pragma once
// The Vulkan device choice from the process environment: the one place the Vulkan libraries read
// it (docs/backends.md, "Device choice"). A caller that passes its own ContextOptions
// (BackendRequest::vulkan) gets exactly those; the environment only fills what no caller gave.
//   MASAV_VK_DEVICE       the device: an index or part of its name, as `masav info` lists them
//   MASAV_VK_VALIDATION   1/on/true: the Khronos validation layer with a debug messenger
//   MASAV_VULKAN_LOADER   the loader library to open (default libvulkan.so.1); the tests name a
//                         missing one to play a machine without Vulkan
// An empty value counts as unset.
#include <string>

#include "compute/device/vk_context.h"

namespace masav::vk {

// The device selector and validation from the environment; every other field at its default.
// Throws masav::Error naming the variable on a value it cannot take.
ContextOptions options_from_env();

// The Vulkan loader library's name: MASAV_VULKAN_LOADER, else libvulkan.so.1.
std::string loader_library();

// What is wrong with the driver manifests the loader's own variables name (VK_DRIVER_FILES,
// VK_ICD_FILENAMES: files or directories separated by ':'), for the message when the loader
// finds no usable driver: a missing or unreadable file, one that is not a manifest (no "ICD"
// object with a "library_path"), or a manifest whose absolute library_path does not exist.
// "" when nothing names a manifest or every named one looks right.
std::string driver_manifest_problem();

}  // namespace masav::vk

#pragma once
// Vulkan-Hpp configuration shared by the backend: the loader is opened at run time
// (libvulkan.so.1 via dlopen), so masav starts and reports a clear error on a machine without
// it instead of failing to link.
// masav opens the loader itself (vk_context.cpp), so Vulkan-Hpp's own loader member, which
// throws when libvulkan is missing, is left out.
#define VULKAN_HPP_ENABLE_DYNAMIC_LOADER_TOOL 0
#ifndef VULKAN_HPP_DISPATCH_LOADER_DYNAMIC
#define VULKAN_HPP_DISPATCH_LOADER_DYNAMIC 1
#endif
#include <vulkan/vulkan_raii.hpp>

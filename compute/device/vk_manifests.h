#pragma once
// Why the Vulkan loader found no usable driver, when the loader's own variables (VK_DRIVER_FILES,
// VK_ICD_FILENAMES) name manifests: their values come from the program (ContextOptions), which
// reads the environment; the library never does.
#include <string>

namespace masav::vk {

// What is wrong with the driver manifests the loader's own variables name (driver_files and
// icd_filenames: the values of VK_DRIVER_FILES and VK_ICD_FILENAMES, files or directories
// separated by ':'), for the message when the loader finds no usable driver: a missing or
// unreadable file, one that is not a manifest (no "ICD" object with a "library_path"), or a
// manifest whose absolute library_path does not exist.
// "" when nothing names a manifest or every named one looks right.
std::string driver_manifest_problem(const std::string& driver_files,
                                    const std::string& icd_filenames);

}  // namespace masav::vk

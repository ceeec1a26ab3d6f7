#include "compute/device/vk_manifests.h"

#include <fmt/format.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <utility>

namespace masav::vk {
namespace {

// The problem with one manifest file, or "".
std::string manifest_problem(const std::string& var, const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const auto st = fs::status(path, ec);
  if (ec || !fs::exists(st)) return fmt::format("{} names '{}', which does not exist", var, path);
  if (fs::is_directory(st)) return "";  // the loader reads the directory's *.json itself
  if (!fs::is_regular_file(st))
    return fmt::format("{} names '{}', which is not a regular file", var, path);
  std::ifstream in(path);
  if (!in) return fmt::format("{} names '{}', which cannot be read", var, path);
  // A manifest is a few hundred bytes; read at most 1 MiB of anything else.
  std::string text(1 << 20, '\0');
  in.read(text.data(), std::streamsize(text.size()));
  text.resize(size_t(in.gcount()));
  const size_t lib = text.find("\"library_path\"");
  const size_t first = text.find_first_not_of(" \t\r\n");
  if (first == std::string::npos || text[first] != '{' ||
      text.find("\"ICD\"") == std::string::npos || lib == std::string::npos)
    return fmt::format("{} names '{}', which is not a Vulkan driver manifest (a JSON object with "
                       "an \"ICD\" object holding a \"library_path\")",
                       var, path);
  // The library path's value: the next quoted string after the key's colon.
  const size_t colon = text.find(':', lib);
  const size_t q0 = colon == std::string::npos ? colon : text.find('"', colon);
  const size_t q1 = q0 == std::string::npos ? q0 : text.find('"', q0 + 1);
  if (q1 == std::string::npos)
    return fmt::format("{} names '{}', whose \"library_path\" has no value", var, path);
  const std::string library = text.substr(q0 + 1, q1 - q0 - 1);
  if (!library.empty() && library[0] == '/' && !fs::exists(library, ec))
    return fmt::format("{} names '{}', whose driver library '{}' does not exist", var, path,
                       library);
  return "";
}

}  // namespace

std::string driver_manifest_problem(const std::string& driver_files,
                                    const std::string& icd_filenames) {
  const std::pair<const char*, const std::string*> vars[] = {{"VK_DRIVER_FILES", &driver_files},
                                                             {"VK_ICD_FILENAMES", &icd_filenames}};
  for (const auto& [var, value] : vars) {
    std::stringstream list(*value);
    std::string path;
    while (std::getline(list, path, ':'))
      if (!path.empty())
        if (std::string p = manifest_problem(var, path); !p.empty()) return p;
  }
  return "";
}

}  // namespace masav::vk

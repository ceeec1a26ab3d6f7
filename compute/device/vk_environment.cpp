#include "compute/device/vk_environment.h"

#include <fmt/format.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "engine/core/error.h"

namespace masav::vk {
namespace {

// The variable's value, or "" where unset or empty.
std::string env(const char* name) {
  const char* v = std::getenv(name);
  return v ? std::string(v) : std::string();
}

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

std::string driver_manifest_problem() {
  for (const char* var : {"VK_DRIVER_FILES", "VK_ICD_FILENAMES"}) {
    std::stringstream list(env(var));
    std::string path;
    while (std::getline(list, path, ':'))
      if (!path.empty())
        if (std::string p = manifest_problem(var, path); !p.empty()) return p;
  }
  return "";
}

ContextOptions options_from_env() {
  ContextOptions o;
  o.device_selector = env("MASAV_VK_DEVICE");
  const std::string v = env("MASAV_VK_VALIDATION");
  if (v == "1" || v == "on" || v == "true")
    o.validation = true;
  else if (v == "0" || v == "off" || v == "false" || v.empty())
    o.validation = false;
  else
    throw Error("", "environment", fmt::format("invalid MASAV_VK_VALIDATION = {}", v),
                "MASAV_VK_VALIDATION must be 1/on/true or 0/off/false");
  return o;
}

std::string loader_library() {
  const std::string name = env("MASAV_VULKAN_LOADER");
  return name.empty() ? "libvulkan.so.1" : name;
}

}  // namespace masav::vk

#include <algorithm>

#include "masav/backends.h"
#include "masav/version.h"
#include "registry/backends.h"

namespace masav {

const char* version() {
  return MASAV_LIBRARY_VERSION;
}

namespace {

VulkanSettings vulkan_settings(const BackendOptions& o) {
  return VulkanSettings{.validation = o.vulkan_validation, .loader = o.vulkan_loader};
}

}  // namespace

std::unique_ptr<Backend> open_backend(const BackendOptions& o) {
  BackendRequest request;
  request.tuning = o.tuning;
  request.cache_dir = o.cache_dir;
  return create_backend(o.name, o.device, request, vulkan_settings(o));
}

std::unique_ptr<Backend> open_backend(std::string_view name) {
  return create_backend(name);
}

std::vector<BackendStatus> backend_report() {
  return list_backends();
}

std::vector<BackendStatus> backend_report(const BackendOptions& options) {
  return list_backends(vulkan_settings(options));
}

std::vector<std::string> usable_backends() {
  std::vector<std::string> names;
  const std::vector<BackendStatus> all = list_backends();
  // Best first: the order `auto` prefers (cuda, vulkan, cpu).
  for (const char* name : {"cuda", "vulkan", "cpu"})
    for (const BackendStatus& s : all)
      if (s.name == name && s.built && s.available) names.push_back(s.name);
  return names;
}

Tuning parse_tuning(std::string_view assignments) {
  Tuning t;
  size_t i = 0;
  while (i < assignments.size()) {
    const size_t start = assignments.find_first_not_of(' ', i);
    if (start == std::string_view::npos) break;
    const size_t end = std::min(assignments.find(' ', start), assignments.size());
    set_tuning(t, assignments.substr(start, end - start));
    i = end;
  }
  return t;
}

}  // namespace masav

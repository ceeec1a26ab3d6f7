#include "engine/kernels/kernel_id.h"

#include <string>

namespace masav {
namespace {

constexpr std::array<std::string_view, kKernelCount> kNames = {
#define MASAV_KERNEL(name, ...) #name,
#include "engine/kernels/kernels.inc"
#undef MASAV_KERNEL
};

}  // namespace

std::string_view kernel_name(KernelId id) {
  const auto i = size_t(id);
  return i < kNames.size() ? kNames[i] : std::string_view("?");
}

std::optional<KernelId> find_kernel(std::string_view name) {
  for (size_t i = 0; i < kNames.size(); ++i)
    if (kNames[i] == name) return KernelId(i);
  return std::nullopt;
}

std::string_view kernel_names_list() {
  static const std::string list = [] {
    std::string s;
    for (std::string_view n : kNames) s += (s.empty() ? "" : ", ") + std::string(n);
    return s;
  }();
  return list;
}

}  // namespace masav

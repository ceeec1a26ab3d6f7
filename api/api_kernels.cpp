#include "masav/kernels.h"

namespace masav {

std::vector<std::string> kernel_list() {
  std::vector<std::string> names;
  for (KernelId k : kAllKernels) names.emplace_back(kernel_name(k));
  return names;
}

std::optional<KernelId> kernel_by_name(std::string_view name) {
  return find_kernel(name);
}

}  // namespace masav

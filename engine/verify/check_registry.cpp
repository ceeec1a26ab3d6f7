// Every kernel check masav knows. A domain adds its checks with one line here.
#include "engine/verify/check_registry.h"

namespace masav::verify {

const std::vector<KernelCheck>& kernel_checks() {
  static const std::vector<KernelCheck> all = [] {
    std::vector<KernelCheck> v;
    for (auto* domain : {
              &foundation_checks, &points_checks, &atom_checks, &sph_checks
         })
      for (auto& c : (*domain)()) v.push_back(std::move(c));
    return v;
  }();
  return all;
}

}  // namespace masav::verify

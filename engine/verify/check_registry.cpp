// Every kernel check masav knows. A domain adds its checks with one line here.
#include "engine/verify/check_registry.h"

namespace masav::verify {

const std::vector<KernelCheck>& kernel_checks() {
  static const std::vector<KernelCheck> all = [] {
    std::vector<KernelCheck> v;
    for (auto* domain : {
             &foundation_checks, &points_checks, &atom_checks,
             // The lead adds: &sph_checks (issue 3), &atom_checks (issue 4).
         })
      for (auto& c : (*domain)()) v.push_back(std::move(c));
    return v;
  }();
  return all;
}

}  // namespace masav::verify

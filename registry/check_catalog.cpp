// Every kernel check masav knows: a domain adds its checks with one line here.
#include "registry/check_catalog.h"

#include "engine/atom/atom_cross_checks.h"
#include "engine/points/points_checks.h"
#include "engine/sph/sph_cross_checks.h"
#include "engine/verify/foundation_checks.h"
#include "registry/backends.h"
#include "registry/scene_catalog.h"

namespace masav::verify {

const std::vector<KernelCheck>& kernel_checks() {
  static const std::vector<KernelCheck> all = [] {
    std::vector<KernelCheck> v;
    for (auto* domain : {&foundation_checks, &points_checks, &atom_checks, &sph_checks})
      for (auto& c : (*domain)()) v.push_back(std::move(c));
    return v;
  }();
  return all;
}

const KernelCheck* find_kernel_check(KernelId kernel) {
  for (const auto& k : kernel_checks())
    if (k.kernel == kernel_name(kernel)) return &k;
  return nullptr;
}

CrossCheckReport cross_check(Backend& backend, Backend& reference,
                             const std::vector<std::string>& kernels, const CheckInputs& in,
                             std::optional<KernelId> fault) {
  return cross_check(backend, reference, kernels, in, kernel_checks(), fault);
}

CrossCheckReport cross_check_scene(Backend& backend, Backend& reference,
                                   const scene::ParamSet& params, std::optional<KernelId> fault) {
  return cross_check_scene(backend, reference,
                           scene::find_scene_type(params.get_text("scene.type")), params,
                           kernel_checks(), fault);
}

std::unique_ptr<Backend> open_reference(const Backend& chosen, const std::string& choice,
                                        const BackendRequest& request) {
  return open_reference(chosen, choice, backend_factory(), request);
}

}  // namespace masav::verify

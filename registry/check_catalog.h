#pragma once
// The cross-checks built into this binary: every domain's kernel checks (check_catalog.cpp
// lists them), and the cross-check of a scene with them, against a reference from the registry.
#include <memory>
#include <string>
#include <vector>

#include "engine/scene/param_schema.h"
#include "engine/verify/cross_check.h"
#include "engine/verify/kernel_check.h"

namespace masav::verify {

const std::vector<KernelCheck>& kernel_checks();
// The built-in check of a kernel (null: none; a test requires one for every kernel).
const KernelCheck* find_kernel_check(KernelId kernel);

// The built-in checks of `kernels` (see verify::cross_check).
CrossCheckReport cross_check(Backend& backend, Backend& reference,
                             const std::vector<std::string>& kernels, const CheckInputs& in,
                             std::optional<KernelId> fault = std::nullopt);
// Every kernel the scene of `params` runs, with the built-in checks.
CrossCheckReport cross_check_scene(Backend& backend, Backend& reference,
                                   const scene::ParamSet& params,
                                   std::optional<KernelId> fault = std::nullopt);
// The reference backend `choice` names, from the backend registry (see verify::open_reference).
std::unique_ptr<Backend> open_reference(const Backend& chosen, const std::string& choice,
                                        const BackendRequest& request = {});

}  // namespace masav::verify

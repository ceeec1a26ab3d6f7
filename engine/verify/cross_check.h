#pragma once
// The cross-check before rendering (SPEC §2): every kernel a scene uses runs on the chosen
// backend and on a second one with identical inputs; the report names each kernel, both
// backends and devices, the errors and the tolerances, and is printed and saved as JSON.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "engine/kernels/backend.h"
#include "engine/kernels/backend_factory.h"
#include "engine/scene/scene.h"
#include "engine/verify/kernel_check.h"

namespace masav::verify {

// A kernel that one backend cannot run (it threw an Error: a buffer over its limit, a feature
// it lacks) was not compared: that is neither agreement nor disagreement, and is counted apart.
struct CheckRow {
  std::string kernel;
  CheckKind kind = CheckKind::exact;
  bool pass = false;
  std::string metrics, tolerance;
  std::map<std::string, double> numbers;
  std::string error;          // the kernel threw (on either backend), or no check exists
  bool not_compared = false;  // one backend refused the kernel: `refused_by`, `error`
  std::string refused_by;     // that backend's name
  uint64_t limit_bytes = 0;   // its per-buffer limit, when the refusal was a size (LimitError)
  std::string advice;         // what fits: the scene's fit_advice, else the refusal's remedy
  double ms_backend = 0, ms_reference = 0;  // wall time of each run, inputs included
};

struct CrossCheckReport {
  std::string scene;  // scene type
  std::string backend, device, reference, reference_device;
  uint32_t points = 0;
  uint64_t seed = 0;
  std::vector<CheckRow> rows;
  bool pass() const;            // every kernel compared and agreeing
  size_t failures() const;      // kernels that disagree, or have no check
  size_t not_compared() const;  // kernels a backend refused
};

// Runs the checks of `kernels` (found in `checks`) on `backend` and `reference`. A kernel
// without a check fails (every kernel a scene uses must be checked). `fault` makes `backend`
// perturb that kernel's output during its own check (Backend::inject_fault): how the tests prove
// a mismatch is caught and stops the run (the command line's hidden --inject-fault).
CrossCheckReport cross_check(Backend& backend, Backend& reference,
                             const std::vector<std::string>& kernels, const CheckInputs& in,
                             const std::vector<KernelCheck>& checks,
                             std::optional<KernelId> fault = std::nullopt);
// Every kernel `type` runs with `params`, on the inputs it asks for.
CrossCheckReport cross_check_scene(Backend& backend, Backend& reference,
                                   const scene::SceneType& type, const scene::ParamSet& params,
                                   const std::vector<KernelCheck>& checks,
                                   std::optional<KernelId> fault = std::nullopt);

// The second backend: `choice` (verify.reference: auto, cpu, vulkan, cuda) from `factory`, with
// the chosen backend's tuning. auto = the other GPU backend if it is available, else the CPU
// reference (a second instance when the chosen backend is the CPU itself and no GPU backend is
// present). `request` is the caller's (its Vulkan loader and validation, its cache directory);
// its tuning is replaced by the chosen backend's.
std::unique_ptr<Backend> open_reference(const Backend& chosen, const std::string& choice,
                                        const BackendFactory& factory,
                                        const BackendRequest& request = {});

std::string format_report(const CrossCheckReport& r);
std::string report_json(const CrossCheckReport& r);
// The one-line reason a failed report stops rendering, with the remedy: the kernels that
// disagree, then those not compared with the backend that refused each and what fits.
std::string failure_summary(const CrossCheckReport& r);

}  // namespace masav::verify

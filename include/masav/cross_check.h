#pragma once
/// \file
/// Cross-checks: a kernel run on two backends with identical inputs and compared with the
/// check `masav verify` runs (integers bit for bit, floats within stated tolerances, random
/// kernels by a chi-square test). The report (`verify::CrossCheckReport`) is the one the command
/// line prints and saves: each kernel, both backends and devices, the errors and tolerances.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "engine/verify/cross_check.h"

namespace masav {

/// Inputs of a kernel's check.
struct CrossCheckOptions {
  /// Points (particles, samples) to check on; empty: as `masav verify` sizes them for the first
  /// scene that runs the kernel.
  std::optional<uint32_t> points;
  /// Seed of the inputs.
  uint64_t seed = 1;
  /// A kernel whose output `backend` perturbs during its own check (a test's way to see that
  /// the check catches a mismatch); none by default.
  std::optional<KernelId> inject_fault;
};

/// Checks `kernel` on `backend` against `reference`. Throws masav::Error for a kernel that does
/// not exist; a disagreement is a failed row of the report, not an exception.
verify::CrossCheckReport cross_check(std::string_view kernel, Backend& backend, Backend& reference,
                                     const CrossCheckOptions& options = {});

/// Checks each of `kernels` (names of the kernel list, or {"all"}) on both backends.
verify::CrossCheckReport cross_check(const std::vector<std::string>& kernels, Backend& backend,
                                     Backend& reference, const CrossCheckOptions& options = {});

/// The report as `masav verify` prints it.
std::string report_text(const verify::CrossCheckReport& report);

/// The report as `masav verify --json` saves it.
std::string report_json_text(const verify::CrossCheckReport& report);

}  // namespace masav

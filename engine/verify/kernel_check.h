#pragma once
// One kernel's cross-check (SPEC §2): run it on two backends with identical inputs and compare.
// Integer kernels must match bit for bit, float kernels within a stated tolerance, statistical
// kernels by a two-sample chi-square. Adding a kernel's check is a few lines with the helpers
// below, e.g.
//
//   exact_check("radix_sort", [](Backend& b, const CheckInputs& in) {
//     ... upload keys, b.radix_sort(...) ...
//     return outputs({{"keys", b.download(keys)}});
//   });
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "engine/kernels/backend.h"
#include "engine/scene/scene.h"

namespace masav::verify {

using scene::CheckInputs;

enum class CheckKind : uint8_t { exact, tolerance, statistical };
const char* check_kind_name(CheckKind k);

// One named output array of a kernel run: words (exact), reals (tolerance), or histogram
// counts (statistical).
struct CheckOutput {
  std::string name;
  std::vector<uint32_t> words;
  std::vector<double> reals;
};
using CheckOutputs = std::vector<CheckOutput>;

struct Tolerance {
  double rel_l2 = 0;   // ||got - want|| / ||want|| at most
  double max_abs = 0;  // and each value within max_abs ...
  double max_rel = 0;  // ... or within max_rel of the reference (relative to rel_floor)
  double rel_floor = 1e-30;
  std::string describe() const;
};

// The outcome of comparing one kernel's outputs.
struct Verdict {
  bool pass = false;
  std::string metrics;                    // what was measured, e.g. "0 of 65536 words differ"
  std::string tolerance;                  // what was allowed, e.g. "bit for bit"
  std::map<std::string, double> numbers;  // the same, for the JSON report
};

struct KernelCheck {
  std::string kernel;
  CheckKind kind = CheckKind::exact;
  std::function<CheckOutputs(Backend&, const CheckInputs&)> run;
  std::function<Verdict(const CheckOutputs& got, const CheckOutputs& want, const CheckInputs&)>
      compare;
};

KernelCheck exact_check(std::string kernel,
                        std::function<CheckOutputs(Backend&, const CheckInputs&)> run);
// The built-in checks name their kernel by KernelId (a typo is a build error).
KernelCheck exact_check(KernelId kernel,
                        std::function<CheckOutputs(Backend&, const CheckInputs&)> run);
KernelCheck tolerance_check(KernelId kernel, Tolerance tol,
                            std::function<CheckOutputs(Backend&, const CheckInputs&)> run);
KernelCheck chi_square_check(KernelId kernel, double min_p,
                             std::function<CheckOutputs(Backend&, const CheckInputs&)> run);
KernelCheck tolerance_check(std::string kernel, Tolerance tol,
                            std::function<CheckOutputs(Backend&, const CheckInputs&)> run);
// Histograms (in `words` or `reals`) pass when the two-sample chi-square's p-value >= min_p.
KernelCheck chi_square_check(std::string kernel, double min_p,
                             std::function<CheckOutputs(Backend&, const CheckInputs&)> run);

// The comparisons the helpers use (exposed for custom checks and tests).
Verdict compare_exact(const CheckOutputs& got, const CheckOutputs& want);
Verdict compare_tolerance(const CheckOutputs& got, const CheckOutputs& want, const Tolerance& tol);
Verdict compare_chi_square(const CheckOutputs& got, const CheckOutputs& want, double min_p);

// Host-side inputs shared by several checks, identical on every backend: points uniform in the
// check grid's box (or the unit cube), as fp32.
std::vector<Vec4f> check_points(const CheckInputs& in);

}  // namespace masav::verify

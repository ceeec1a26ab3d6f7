#pragma once
// Error of a float result against a reference: the numbers the tests assert and the cross-check
// reports (max absolute, max relative with a floor, relative L2).
#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "engine/core/types.h"

namespace masav {

struct ErrorStats {
  double max_abs = 0;     // max |got - want|
  double max_rel = 0;     // max |got - want| / max(|want|, rel_floor)
  double rel_l2 = 0;      // ||got - want||_2 / max(||want||_2, tiny)
  size_t worst = 0;       // index of the largest relative error
  size_t count = 0;
  size_t non_finite = 0;  // NaN or Inf in `got` where `want` is finite
};

// rel_floor keeps relative errors of values near zero meaningful (e.g. 1e-6 of the data scale).
ErrorStats compare(std::span<const double> got, std::span<const double> want, double rel_floor);
ErrorStats compare(std::span<const float> got, std::span<const double> want, double rel_floor);
std::string describe(const ErrorStats& e);

// x, y, z of each vector, flattened (w dropped): what compare() takes for vector data.
std::vector<double> xyz_components(std::span<const Vec4d> v);
// Root mean square of the values (0 for none): the scale of a rel_floor.
double rms(std::span<const double> v);

}  // namespace masav

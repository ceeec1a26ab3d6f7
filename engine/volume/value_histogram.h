#pragma once
// The histogram of a volume's values over [lo, hi] (the range raymarch normalises to [0, 1]),
// which the demo's transfer function editor draws under its control points.
#include <cstdint>
#include <span>
#include <vector>

namespace masav::volume {

// `bins` counts over [lo, hi]: value v falls in bin floor((v - lo) / (hi - lo) * bins), the top
// value in the last bin. Values outside [lo, hi] count at its ends, as raymarch clamps them;
// non-finite ones are not counted. A range of zero width counts every value in bin 0.
std::vector<uint32_t> value_histogram(std::span<const double> values, double lo, double hi,
                                      uint32_t bins);

// Heights in [0, 1] for drawing: log(1 + count) / log(1 + the largest count), so that the few
// voxels of a volume's bright core still show beside its empty space.
std::vector<float> log_heights(const std::vector<uint32_t>& counts);

}  // namespace masav::volume

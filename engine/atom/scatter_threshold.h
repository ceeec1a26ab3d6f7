#pragma once
// The scattering table drops a photon when its weight albedo^k falls below weight_threshold.
// The GPU multiplies the weight in fp32 and the CPU reference in double: where a power of the
// albedo lies within rounding of the threshold (albedo 0.01: 0.01^2 against 1e-4), the two drop
// photons after different numbers of scatterings and tally different tables. This moves such a
// threshold to the geometric middle of two consecutive powers of the albedo (a power equal to
// it is kept, as in exact arithmetic), where both precisions agree; any other threshold is
// returned as it is.
#include <cstdint>

namespace masav::atom {

float separated_weight_threshold(float albedo, float threshold, uint32_t max_scatterings);

}  // namespace masav::atom

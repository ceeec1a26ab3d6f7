#pragma once
// How far drift_points' output on one backend is from another's, and how far it may be: the
// stated tolerance both the kernel tests and the cross-check use. Positions wrap around the
// periodic box, so a point that wrapped on one backend and not on the other (its fraction was
// within rounding of 0 or 1) is compared by its periodic distance, which is tiny.
#include <span>

#include "engine/core/types.h"
#include "engine/kernels/drift_params.h"

namespace masav {

struct DriftError {
  double max_position_abs = 0;  // largest periodic per-axis difference, world units
  double max_speed_rel = 0;     // largest relative difference of .w
  size_t worst = 0;             // index of the largest position difference
  size_t non_finite = 0;
};

struct DriftTolerance {
  double position_abs = 0;  // world units
  double speed_rel = 0;
};

DriftError compare_drift(const DriftParams& p, std::span<const Vec4d> got,
                         std::span<const Vec4d> want);
// fp32 rounding of each step of the drift (a few units in the last place of the fraction and of
// the box coordinates), times a safety factor of 4.
DriftTolerance drift_tolerance(const DriftParams& p);

}  // namespace masav

#pragma once
// What the SPH and DFSPH cross-checks share (engine/sph/sph_cross_checks.cpp,
// engine/sph/dfsph_cross_checks.cpp): the particle case and a check comparing each named output
// with its own tolerance.
#include <functional>
#include <string>
#include <vector>

#include "engine/kernels/backend.h"
#include "engine/verify/kernel_check.h"

namespace masav::verify {

struct SphCheckCase {
  std::vector<Vec4f> positions, velocities;
  SphStepParams params;
};

// side^3 particles at spacing dx = 1 cm (h = 2 dx), jittered by 0.3 dx, velocities up to
// 0.3 m/s; every 37th particle pinned, some 1000x heavier; the box's walls lie just outside the
// lattice (0.1-0.3 dx beyond its outermost jitter, as a run keeps every particle inside), so
// the outer layers see their wall images. side follows the scene's check point count, capped so the
// check stays quick on any backend.
SphCheckCase make_sph_check_case(const CheckInputs& in, SphPressureModel model);

// Outputs compared one by one, each with its tolerance; `scaled` tolerances measure errors
// relative to the reference output's RMS (times rel_floor) plus `floor_abs`.
struct OutputTolerance {
  std::string prefix;  // applies to outputs whose name starts with it
  Tolerance tol;
  bool rms_floor = false;
  double floor_abs = 0;
};

KernelCheck per_output_check(KernelId kernel, std::vector<OutputTolerance> tols,
                             std::function<CheckOutputs(Backend&, const CheckInputs&)> run);

}  // namespace masav::verify

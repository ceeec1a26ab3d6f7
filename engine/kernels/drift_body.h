#pragma once
// The periodic drift of `drift_points` (engine/kernels/drift_params.h), shared by the CPU
// reference (in double) and CUDA (in float, one rounding per operation as GLSL `precise` does).
// shaders/common/drift.glsl is the GLSL twin.
#include <cmath>

#include "engine/core/hd.h"

namespace masav::drift {

MASAV_HD inline float mul(float a, float b) {
  return hd::mul_rn(a, b);
}
MASAV_HD inline float add(float a, float b) {
  return hd::add_rn(a, b);
}
MASAV_HD inline float sub(float a, float b) {
  return hd::sub_rn(a, b);
}
MASAV_HD inline double mul(double a, double b) {
  return a * b;
}
MASAV_HD inline double add(double a, double b) {
  return a + b;
}
MASAV_HD inline double sub(double a, double b) {
  return a - b;
}

// Fraction of the box along one axis at displacement `speed_t` = speed * time: in [0, 1).
template <class F>
MASAV_HD inline F axis_fraction(F u, F w, F speed_t) {
  const F dir = sub(mul(F(2), w), F(1));
  const F f = add(u, mul(dir, speed_t));
  F r = sub(f, floor(f));
  // f - floor(f) rounds up to 1 for tiny negative f; 1 would put the point on the far face.
  if (!(r < F(1))) r = F(0);
  return r;
}

// Velocity along one axis in world units per second.
template <class F>
MASAV_HD inline F axis_velocity(F w, F speed, F extent) {
  return mul(mul(sub(mul(F(2), w), F(1)), speed), extent);
}

MASAV_HD inline float sqrt_rn(float a) {
  return hd::sqrt_rn(a);
}
MASAV_HD inline double sqrt_rn(double a) {
  return sqrt(a);
}

}  // namespace masav::drift

namespace masav {

template <>
struct KernelBody<KernelId::drift_points> {
  static constexpr uint32_t kCpuGrain = 8192;
  // positions[i] = the drift of point i at p.time_s; .w its speed.
  template <class F, class Diag>
  MASAV_HD static void run(uint32_t i, const DriftParams& p, Diag&, const float* start,
                           const float* direction, hd::V4<F>* positions) {
    using namespace drift;
    const float lo[3] = {p.box_lo.x, p.box_lo.y, p.box_lo.z};
    const float ext[3] = {p.box_extent.x, p.box_extent.y, p.box_extent.z};
    const F speed_t = mul(F(p.speed), F(p.time_s));
    F x[3];
    F v2 = F(0);
    for (int a = 0; a < 3; ++a) {
      const F u = F(start[4 * i + a]), w = F(direction[4 * i + a]);
      x[a] = add(F(lo[a]), mul(F(ext[a]), axis_fraction(u, w, speed_t)));
      const F v = axis_velocity(w, F(p.speed), F(ext[a]));
      v2 = add(v2, mul(v, v));
    }
    positions[i] = hd::V4<F>{x[0], x[1], x[2], sqrt_rn(v2)};
  }
};

}  // namespace masav

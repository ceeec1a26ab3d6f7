#pragma once
// The periodic drift of `drift_points` (engine/points/drift_params.h), shared by the CPU
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

}  // namespace masav::drift

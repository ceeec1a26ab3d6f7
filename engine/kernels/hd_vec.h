#pragma once
// A small 3-vector and float/double math wrappers that compile the same for the CPU reference
// (double) and CUDA (float): the atom kernels' shared MASAV_HD code is templated on T and calls
// these, never std:: functions, so one body runs on both.
#include <math.h>

#include "engine/core/hd.h"

namespace masav::hd {

// The float function (sqrtf, ...) for float, the double one for double: what CUDA and the host
// both resolve without std::.
#define MASAV_HD_MATH1(name)                                         \
  template <class T>                                                 \
  MASAV_HD inline T name##_t(T x) {                                  \
    if constexpr (sizeof(T) == sizeof(float)) return name##f(x);     \
    else return name(x);                                             \
  }
MASAV_HD_MATH1(sqrt)
MASAV_HD_MATH1(log)
MASAV_HD_MATH1(exp)
MASAV_HD_MATH1(sin)
MASAV_HD_MATH1(cos)
MASAV_HD_MATH1(cbrt)
MASAV_HD_MATH1(floor)
MASAV_HD_MATH1(ceil)
#undef MASAV_HD_MATH1
template <class T>
MASAV_HD inline T pow_t(T x, T y) {
  if constexpr (sizeof(T) == sizeof(float)) return powf(x, y);
  else return pow(x, y);
}
template <class T>
MASAV_HD inline T min_t(T a, T b) { return a < b ? a : b; }
template <class T>
MASAV_HD inline T max_t(T a, T b) { return a > b ? a : b; }
template <class T>
MASAV_HD inline T clamp_t(T v, T lo, T hi) { return v < lo ? lo : (v > hi ? hi : v); }
template <class T>
MASAV_HD inline T abs_t(T v) { return v < T(0) ? -v : v; }

template <class T>
struct V3 {
  T x, y, z;
};
template <class T>
MASAV_HD inline V3<T> operator+(V3<T> a, V3<T> b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
template <class T>
MASAV_HD inline V3<T> operator-(V3<T> a, V3<T> b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
template <class T>
MASAV_HD inline V3<T> operator*(V3<T> a, T s) { return {a.x * s, a.y * s, a.z * s}; }
template <class T>
MASAV_HD inline V3<T> operator*(T s, V3<T> a) { return {s * a.x, s * a.y, s * a.z}; }
template <class T>
MASAV_HD inline T dot(V3<T> a, V3<T> b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
template <class T>
MASAV_HD inline V3<T> cross(V3<T> a, V3<T> b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
template <class T>
MASAV_HD inline T length(V3<T> a) { return sqrt_t(dot(a, a)); }
template <class T>
MASAV_HD inline V3<T> normalize(V3<T> a) { return a * (T(1) / length(a)); }
template <class T>
MASAV_HD inline T comp(V3<T> a, int i) { return i == 0 ? a.x : (i == 1 ? a.y : a.z); }

}  // namespace masav::hd

#pragma once
// A small 3-vector and float/double math wrappers that compile the same for the CPU reference
// (double) and CUDA (float): the atom kernels' shared MASAV_HD code is templated on T and calls
// these, never std:: functions, so one body runs on both.
#include <math.h>

#include "engine/core/hd.h"

namespace masav::hd {

MASAV_HD inline float sqrt_t(float x) { return sqrtf(x); }
MASAV_HD inline double sqrt_t(double x) { return sqrt(x); }
MASAV_HD inline float log_t(float x) { return logf(x); }
MASAV_HD inline double log_t(double x) { return log(x); }
MASAV_HD inline float exp_t(float x) { return expf(x); }
MASAV_HD inline double exp_t(double x) { return exp(x); }
MASAV_HD inline float sin_t(float x) { return sinf(x); }
MASAV_HD inline double sin_t(double x) { return sin(x); }
MASAV_HD inline float cos_t(float x) { return cosf(x); }
MASAV_HD inline double cos_t(double x) { return cos(x); }
MASAV_HD inline float pow_t(float x, float y) { return powf(x, y); }
MASAV_HD inline double pow_t(double x, double y) { return pow(x, y); }
MASAV_HD inline float cbrt_t(float x) { return cbrtf(x); }
MASAV_HD inline double cbrt_t(double x) { return cbrt(x); }
MASAV_HD inline float floor_t(float x) { return floorf(x); }
MASAV_HD inline double floor_t(double x) { return floor(x); }
MASAV_HD inline float ceil_t(float x) { return ceilf(x); }
MASAV_HD inline double ceil_t(double x) { return ceil(x); }
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
MASAV_HD inline T dot(V3<T> a, V3<T> b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
template <class T>
MASAV_HD inline T length(V3<T> a) { return sqrt_t(dot(a, a)); }
template <class T>
MASAV_HD inline V3<T> normalize(V3<T> a) { return a * (T(1) / length(a)); }
template <class T>
MASAV_HD inline T comp(V3<T> a, int i) { return i == 0 ? a.x : (i == 1 ? a.y : a.z); }

}  // namespace masav::hd

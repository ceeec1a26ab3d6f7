#pragma once
// MASAV_HD marks math that the CPU reference and the CUDA kernels share: the CPU tests then run
// the very code the CUDA kernels call. The *_rn helpers pin each fp32 operation to one rounding
// (no FMA contraction), matching GLSL `precise`, for results that must agree bit for bit.
#if defined(__CUDACC__)
#define MASAV_HD __host__ __device__
#else
#define MASAV_HD
#endif

#include <math.h>
#include <stdint.h>
#if !defined(__CUDA_ARCH__)
#include <atomic>
#endif

namespace masav::hd {

MASAV_HD inline float add_rn(float a, float b) {
#if defined(__CUDA_ARCH__)
  return __fadd_rn(a, b);
#else
  return a + b;
#endif
}
MASAV_HD inline float sub_rn(float a, float b) {
#if defined(__CUDA_ARCH__)
  return __fsub_rn(a, b);
#else
  return a - b;
#endif
}
MASAV_HD inline float mul_rn(float a, float b) {
#if defined(__CUDA_ARCH__)
  return __fmul_rn(a, b);
#else
  return a * b;
#endif
}
MASAV_HD inline float sqrt_rn(float a) {
#if defined(__CUDA_ARCH__)
  return __fsqrt_rn(a);
#else
  return sqrtf(a);
#endif
}

// *p += v as one atomic step, returning the old value: bodies that count into shared cells run
// concurrently on the CPU reference's thread pool as on the GPU. Relaxed: integer sums come out
// the same in any order.
MASAV_HD inline uint32_t atomic_add(uint32_t* p, uint32_t v) {
#if defined(__CUDA_ARCH__)
  return atomicAdd(p, v);
#else
  return std::atomic_ref<uint32_t>(*p).fetch_add(v, std::memory_order_relaxed);
#endif
}

// One element of a Real4 buffer as a kernel body sees it: four F (double on the CPU reference,
// float on CUDA, where the 16-byte alignment gives one vector load like float4).
template <class F>
struct alignas(16) V4 {
  F x, y, z, w;
};

}  // namespace masav::hd

#pragma once
// Small host-side value types shared by the kernel parameter structs. Plain aggregates with the
// layout GLSL std430 and CUDA expect (Vec4f is 16 bytes, like vec4 and float4).
#include <cstdint>

namespace masav {

struct Vec3f {
  float x = 0, y = 0, z = 0;
};
struct Vec4f {
  float x = 0, y = 0, z = 0, w = 0;
};
struct Vec3d {
  double x = 0, y = 0, z = 0;
};
struct Vec4d {
  double x = 0, y = 0, z = 0, w = 0;
};
struct UVec3 {
  uint32_t x = 0, y = 0, z = 0;
};

// A 64-bit value as two 32-bit words, low first: how GLSL (uvec2) and every layout hold it.
struct U64 {
  uint32_t lo = 0, hi = 0;
  constexpr U64() = default;
  constexpr U64(uint64_t v) : lo(uint32_t(v)), hi(uint32_t(v >> 32)) {}  // NOLINT: implicit
  constexpr operator uint64_t() const { return uint64_t(hi) << 32 | lo; }
};

// Element tags for buffers whose precision depends on the backend: fp32 on the GPU backends,
// fp64 on the CPU reference, so that the reference keeps double precision across steps.
struct Real {};
struct Real4 {};

}  // namespace masav

// The dialect of the kernels' parameter layouts (engine/kernels/*_params.h). A layout header
// compiles as C++, as CUDA and as GLSL: the host fills the struct, the CUDA kernel takes it by
// value, the CPU reference reads it, and the shader includes the same header and declares the
// struct as its push block (MASAV_PUSH), so no backend copies the fields by hand.
//
// Rules of a layout, so that C++ and GLSL (std430) place every field at the same offset:
//  - scalars are float and uint (4 bytes); a flag is a uint (0 or 1); an enum is
//    MASAV_ENUM(Type): the enum class in C++ (32-bit), uint in GLSL;
//  - vec3/uvec3 and vec4 start at a multiple of 16 (std430 aligns them so); put a 4-byte field
//    after each vec3, so that C++, which aligns Vec3f to 4, packs like std430;
//  - a 64-bit value is MASAV_U64 (two words, low first: uvec2 in GLSL) at a multiple of 8;
//  - a nested layout starts at a multiple of 16 and holds a vec3 or vec4 (std430 then aligns it
//    to 16, as alignas(16) does in C++);
//  - a constant both sides use is MASAV_CONSTANT(name, value) (MASAV_CONSTANT64 for 64 bits);
//  - defaults are written MASAV_INIT(value) (C++ only: GLSL members have no initialisers);
//  - every header asserts, in C++, the size and the offset of every field (MASAV_LAYOUT_CHECK).
// A layout templated on the real type (MASAV_REAL_LAYOUT, fields of type real_t) is read in
// double by the CPU reference and in float everywhere else; its float form is the one asserted.
#ifndef MASAV_CORE_LAYOUT_H
#define MASAV_CORE_LAYOUT_H

#ifdef __cplusplus
#include <cstddef>
#include <cstdint>

#include "engine/core/pp.h"
#include "engine/core/types.h"

#define MASAV_LAYOUT(Name) struct alignas(16) Name
#define MASAV_REAL_LAYOUT(Name) \
  template <class real_t>       \
  struct alignas(16) Name
#define MASAV_INIT(value) = value
#define MASAV_ENUM(Type) Type
#define MASAV_U64 ::masav::U64
#define MASAV_ENUM_BEGIN(Type) enum class Type : uint32_t {
#define MASAV_ENUMERATOR(Type, name, value) name = value,
#define MASAV_ENUM_END(Type) \
  }                          \
  ;
#define MASAV_CONSTANT(name, value) inline constexpr uint32_t name = value;
#define MASAV_CONSTANT64(name, hi, lo) \
  inline constexpr uint64_t name = (uint64_t(hi) << 32) | uint64_t(lo);
// MASAV_LAYOUT_CHECK(Type, bytes, (field, offset)...): the size and every field's offset, as
// std430 places them (C++ only: the header's own numbers, checked by the compiler).
#define MASAV_LAYOUT_CHECK(Type, bytes, ...)                                  \
  static_assert(sizeof(Type) == (bytes), "sizeof(" #Type ") is not " #bytes); \
  MASAV_PP_EACH(MASAV_LAYOUT_OFFSET_I, Type, __VA_ARGS__)
#define MASAV_LAYOUT_OFFSET_I(Type, field, offset) \
  static_assert(offsetof(Type, field) == (offset), \
                #Type "::" #field " is not at std430 offset " #offset);
#define MASAV_NAMESPACE_BEGIN namespace masav {
#define MASAV_NAMESPACE_END }

namespace masav {
using uint = std::uint32_t;
using vec3 = Vec3f;
using vec4 = Vec4f;
using uvec3 = UVec3;
}  // namespace masav

#else  // GLSL

#define MASAV_LAYOUT(Name) struct Name
#define MASAV_REAL_LAYOUT(Name) struct Name
#define real_t float
#define MASAV_INIT(value)
#define MASAV_ENUM(Type) uint
#define MASAV_U64 uvec2
#define MASAV_ENUM_BEGIN(Type)
#define MASAV_ENUMERATOR(Type, name, value) const uint Type##_##name = uint(value);
#define MASAV_ENUM_END(Type)
#define MASAV_CONSTANT(name, value) const uint name = uint(value);
#define MASAV_CONSTANT64(name, hi, lo) const uvec2 name = uvec2(lo, hi);
#define MASAV_NAMESPACE_BEGIN
#define MASAV_NAMESPACE_END
// A kernel's parameters as its push block, read as `p.field` like the C++ and CUDA code: `p` is
// a private copy that the kernel's main makes before anything else (MASAV_LOAD_PUSH). lavapipe
// loads a push constant lane by lane, from memory, wherever a loop reads it; the copy made before
// the loops stays in registers (sph_forces at 32,768 particles: 8.1 -> 7.2 ms). A GPU compiler
// reads the copied fields from the push constants where they are used.
#define MASAV_PUSH(Layout)                              \
  layout(push_constant, std430) uniform Layout##Block { \
    Layout push_block_;                                 \
  };                                                    \
  Layout p
#define MASAV_LOAD_PUSH() p = push_block_

#endif
#endif

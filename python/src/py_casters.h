#pragma once
// Python values of masav's small value types: Vec3f, Vec3d, Vec4f and UVec3 are tuples (any
// sequence of numbers of the right length is taken), U64 is an int.
#include <pybind11/pybind11.h>

#include "engine/core/types.h"

namespace pybind11::detail {

template <class V, class E, int N>
struct masav_vec_caster {
  PYBIND11_TYPE_CASTER(V, _("tuple"));

  bool load(handle src, bool convert) {
    if (!src || !PySequence_Check(src.ptr()) || PyUnicode_Check(src.ptr())) return false;
    auto seq = reinterpret_borrow<sequence>(src);
    if (seq.size() != size_t(N)) return false;
    E* out = reinterpret_cast<E*>(&value);
    for (int i = 0; i < N; ++i) {
      make_caster<E> c;
      if (!c.load(seq[size_t(i)], convert)) return false;
      out[i] = cast_op<E>(c);
    }
    return true;
  }

  static handle cast(const V& v, return_value_policy, handle) {
    const E* in = reinterpret_cast<const E*>(&v);
    tuple t(N);
    for (int i = 0; i < N; ++i) t[size_t(i)] = pybind11::cast(in[i]);
    return t.release();
  }
};

template <>
struct type_caster<masav::Vec3f> : masav_vec_caster<masav::Vec3f, float, 3> {};
template <>
struct type_caster<masav::Vec4f> : masav_vec_caster<masav::Vec4f, float, 4> {};
template <>
struct type_caster<masav::Vec3d> : masav_vec_caster<masav::Vec3d, double, 3> {};
template <>
struct type_caster<masav::UVec3> : masav_vec_caster<masav::UVec3, uint32_t, 3> {};

template <>
struct type_caster<masav::U64> {
  PYBIND11_TYPE_CASTER(masav::U64, _("int"));
  bool load(handle src, bool convert) {
    make_caster<uint64_t> c;
    if (!c.load(src, convert)) return false;
    value = masav::U64(cast_op<uint64_t>(c));
    return true;
  }
  static handle cast(const masav::U64& v, return_value_policy, handle) {
    return PyLong_FromUnsignedLongLong(uint64_t(v));
  }
};

}  // namespace pybind11::detail

#pragma once
// The preprocessor pieces that expand engine/kernels/kernels.inc: a kernel's buffers are written
// once there as (access, Elem, name, binding) and become parameter lists, argument lists, names
// and the Vulkan backend's binding table here.
//
// access   C++ parameter                 meaning
// in       const Buffer<Elem>&           read
// out      Buffer<Elem>&                 written
// inout    Buffer<Elem>&                 read and written
// opt_in   const Buffer<Elem>*           read when not null
// opt_out  Buffer<Elem>*                 written when not null
// opt_inout Buffer<Elem>*                read or written when not null (the params say which)
// any_in   const BufferImpl&             read, any element type (Elem is a placeholder)
// any_out  BufferImpl&                   written, any element type
//
// binding  how a Vulkan shader declares the buffer (the other backends ignore it)
// storage  a storage buffer
// texel    a uniform texel buffer, one texel per element, of the element's format: Real4
//          rgba32f, Real and float r32f, uint32_t r32ui (any_in: the element size, per call)
// Any other word is a compile error in every build (MASAV_BUFFER_BINDING_CHECK_).

#include "engine/core/pp.h"

#define MASAV_BUFFER_TYPE_in(elem) const Buffer<elem>&
#define MASAV_BUFFER_TYPE_out(elem) Buffer<elem>&
#define MASAV_BUFFER_TYPE_inout(elem) Buffer<elem>&
#define MASAV_BUFFER_TYPE_opt_in(elem) const Buffer<elem>*
#define MASAV_BUFFER_TYPE_opt_out(elem) Buffer<elem>*
#define MASAV_BUFFER_TYPE_opt_inout(elem) Buffer<elem>*
#define MASAV_BUFFER_TYPE_any_in(elem) const BufferImpl&
#define MASAV_BUFFER_TYPE_any_out(elem) BufferImpl&

// The element type as a type: void for the any_* buffers, whose element is chosen per call.
#define MASAV_BUFFER_ELEM_in(elem) elem
#define MASAV_BUFFER_ELEM_out(elem) elem
#define MASAV_BUFFER_ELEM_inout(elem) elem
#define MASAV_BUFFER_ELEM_opt_in(elem) elem
#define MASAV_BUFFER_ELEM_opt_out(elem) elem
#define MASAV_BUFFER_ELEM_opt_inout(elem) elem
#define MASAV_BUFFER_ELEM_any_in(elem) void
#define MASAV_BUFFER_ELEM_any_out(elem) void

// The binding kinds there are; each expands to nothing, so that an unknown word leaves an
// undeclared name where the buffer's name is expanded (MASAV_BUFFER_NAME, in every build).
#define MASAV_BUFFER_BINDING_CHECK_storage
#define MASAV_BUFFER_BINDING_CHECK_texel

#define MASAV_BUFFER_PARAM(d, access, elem, name, binding) , MASAV_BUFFER_TYPE_##access(elem) name
#define MASAV_BUFFER_ARG(d, access, elem, name, binding) , name
#define MASAV_BUFFER_MEMBER(d, access, elem, name, binding) MASAV_BUFFER_TYPE_##access(elem) name;
#define MASAV_BUFFER_NAME(d, access, elem, name, binding) \
  MASAV_BUFFER_BINDING_CHECK_##binding #name,
#define MASAV_BUFFER_BINDING(m, access, elem, name, binding) \
  m(binding, MASAV_BUFFER_ELEM_##access(elem)),
// ", const Buffer<float>& start, Buffer<Real4>& positions" (each with its leading comma).
#define MASAV_BUFFER_PARAMS(...) MASAV_PP_EACH(MASAV_BUFFER_PARAM, _, __VA_ARGS__)
// ", start, positions".
#define MASAV_BUFFER_ARGS(...) MASAV_PP_EACH(MASAV_BUFFER_ARG, _, __VA_ARGS__)
// "const Buffer<float>& start; Buffer<Real4>& positions;"
#define MASAV_BUFFER_MEMBERS(...) MASAV_PP_EACH(MASAV_BUFFER_MEMBER, _, __VA_ARGS__)
// "start", "positions",
#define MASAV_BUFFER_NAMES(...) MASAV_PP_EACH(MASAV_BUFFER_NAME, _, __VA_ARGS__)
// m(binding, Elem) for each buffer, each with a trailing comma: "m(storage, float), m(texel,
// Real4)," (the Vulkan backend's table, compute/vk_bindings.h).
#define MASAV_BUFFER_BINDINGS(m, ...) MASAV_PP_EACH(MASAV_BUFFER_BINDING, m, __VA_ARGS__)

// A backend's override of one kernel; backends declare them all with
//   #define MASAV_KERNEL MASAV_KERNEL_OVERRIDE
//   #include "engine/kernels/kernels.inc"
//   #undef MASAV_KERNEL
// and define them in one file with MASAV_KERNEL_FORWARD(Class), which hands each call to the
// backend's member template run_kernel<KernelId::name>(p, items, buffers...).
#define MASAV_KERNEL_OVERRIDE(name, Params, items, ...) \
  void do_##name(const Params& p, uint64_t items_ MASAV_BUFFER_PARAMS(__VA_ARGS__)) override;
#define MASAV_KERNEL_FORWARD(Class, name, Params, ...)                                       \
  void Class::do_##name(const Params& p, uint64_t items_ MASAV_BUFFER_PARAMS(__VA_ARGS__)) { \
    run_kernel<KernelId::name>(p, items_ MASAV_BUFFER_ARGS(__VA_ARGS__));                    \
  }

// One call's arguments as a struct, KernelArgs<KernelId::name>{p, items, buffers...}: what a
// backend's own implementation receives (see MASAV_KERNEL_OWN).
#define MASAV_KERNEL_ARGS(name, Params, items, ...) \
  template <>                                       \
  struct KernelArgs<KernelId::name> {               \
    const Params& p;                                \
    uint64_t items_;                                \
    MASAV_BUFFER_MEMBERS(__VA_ARGS__)               \
  };

// A backend's own implementation of one kernel, run_own(const KernelArgs<KernelId::name>&).
// Backends declare one for every kernel and define only those they implement themselves (a
// kernel without a shared body, or a multi-pass one); run_kernel calls it only for those, so the
// others need no definition.
#define MASAV_KERNEL_OWN(name, Params, items, ...) \
  void run_own(const KernelArgs<KernelId::name>& a);

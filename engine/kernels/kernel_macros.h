#pragma once
// The preprocessor pieces that expand engine/kernels/kernels.inc: a kernel's buffers are written
// once there as (access, Elem, name) and become parameter lists, argument lists and names here.
//
// access   C++ parameter                 meaning
// in       const Buffer<Elem>&           read
// out      Buffer<Elem>&                 written
// inout    Buffer<Elem>&                 read and written
// opt_in   const Buffer<Elem>*           read when not null
// opt_out  Buffer<Elem>*                 written when not null
// any_in   const BufferImpl&             read, any element type (Elem is a placeholder)
// any_out  BufferImpl&                   written, any element type

#define MASAV_PP_CAT(a, b) MASAV_PP_CAT_I(a, b)
#define MASAV_PP_CAT_I(a, b) a##b
#define MASAV_PP_COUNT(...) MASAV_PP_COUNT_I(__VA_ARGS__, 12, 11, 10, 9, 8, 7, 6, 5, 4, 3, 2, 1, 0)
#define MASAV_PP_COUNT_I(a1, a2, a3, a4, a5, a6, a7, a8, a9, a10, a11, a12, n, ...) n
// m applied to each parenthesised tuple: MASAV_PP_EACH(m, (a, b), (c, d)) -> m(a, b) m(c, d).
#define MASAV_PP_EACH(m, ...) \
  MASAV_PP_CAT(MASAV_PP_EACH_, MASAV_PP_COUNT(__VA_ARGS__))(m, __VA_ARGS__)
#define MASAV_PP_EACH_1(m, x) m x
#define MASAV_PP_EACH_2(m, x, ...) m x MASAV_PP_EACH_1(m, __VA_ARGS__)
#define MASAV_PP_EACH_3(m, x, ...) m x MASAV_PP_EACH_2(m, __VA_ARGS__)
#define MASAV_PP_EACH_4(m, x, ...) m x MASAV_PP_EACH_3(m, __VA_ARGS__)
#define MASAV_PP_EACH_5(m, x, ...) m x MASAV_PP_EACH_4(m, __VA_ARGS__)
#define MASAV_PP_EACH_6(m, x, ...) m x MASAV_PP_EACH_5(m, __VA_ARGS__)
#define MASAV_PP_EACH_7(m, x, ...) m x MASAV_PP_EACH_6(m, __VA_ARGS__)
#define MASAV_PP_EACH_8(m, x, ...) m x MASAV_PP_EACH_7(m, __VA_ARGS__)
#define MASAV_PP_EACH_9(m, x, ...) m x MASAV_PP_EACH_8(m, __VA_ARGS__)
#define MASAV_PP_EACH_10(m, x, ...) m x MASAV_PP_EACH_9(m, __VA_ARGS__)
#define MASAV_PP_EACH_11(m, x, ...) m x MASAV_PP_EACH_10(m, __VA_ARGS__)
#define MASAV_PP_EACH_12(m, x, ...) m x MASAV_PP_EACH_11(m, __VA_ARGS__)

#define MASAV_BUFFER_TYPE_in(elem) const Buffer<elem>&
#define MASAV_BUFFER_TYPE_out(elem) Buffer<elem>&
#define MASAV_BUFFER_TYPE_inout(elem) Buffer<elem>&
#define MASAV_BUFFER_TYPE_opt_in(elem) const Buffer<elem>*
#define MASAV_BUFFER_TYPE_opt_out(elem) Buffer<elem>*
#define MASAV_BUFFER_TYPE_any_in(elem) const BufferImpl&
#define MASAV_BUFFER_TYPE_any_out(elem) BufferImpl&

#define MASAV_BUFFER_PARAM(access, elem, name) , MASAV_BUFFER_TYPE_##access(elem) name
#define MASAV_BUFFER_ARG(access, elem, name) , name
#define MASAV_BUFFER_NAME(access, elem, name) #name,
// ", const Buffer<float>& start, Buffer<Real4>& positions" (each with its leading comma).
#define MASAV_BUFFER_PARAMS(...) MASAV_PP_EACH(MASAV_BUFFER_PARAM, __VA_ARGS__)
// ", start, positions".
#define MASAV_BUFFER_ARGS(...) MASAV_PP_EACH(MASAV_BUFFER_ARG, __VA_ARGS__)
// "start", "positions",
#define MASAV_BUFFER_NAMES(...) MASAV_PP_EACH(MASAV_BUFFER_NAME, __VA_ARGS__)

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

// A backend's own implementation of one kernel, run_own(KernelTag<KernelId::name>, p, items,
// buffers...). Backends declare one for every kernel and define only those they implement
// themselves (a kernel without a shared body, or a multi-pass one); run_kernel calls it only for
// those, so the others need no definition.
#define MASAV_KERNEL_OWN(name, Params, items, ...)         \
  void run_own(KernelTag<KernelId::name>, const Params& p, \
               uint64_t items_ MASAV_BUFFER_PARAMS(__VA_ARGS__));

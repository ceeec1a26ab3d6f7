#pragma once
// Whole per-element bodies. KernelBody<K>::run<F>(i, params, diag, buffers...) is invocation i
// of kernel K in the precision F: the CPU reference calls it in double on its thread pool
// (engine/cpu/cpu_elementwise.h), CUDA in float from one generic launcher
// (cuda_ref/cuda_elementwise.cuh), so the CPU tests run exactly the code CUDA runs. The GLSL
// shader of the kernel is the independent twin the cross-check compares with.
//
// A body is a specialisation in the header of its kernel's group (engine/kernels/*_body.h):
//   template <> struct KernelBody<KernelId::name> {
//     static constexpr uint32_t kCpuGrain = 8192;  // invocations per CPU task
//     template <class F, class Diag>
//     MASAV_HD static void run(uint32_t i, const Layout& p, Diag& diag, buffer pointers...);
//   };
// Buffer pointers follow the kernel's buffers in kernels.inc: `const T*` for in, `T*` for out,
// where T is the element (uint32_t, float) or, for Real and Real4, F and hd::V4<F>.
// diag.report(flag, index) raises a kDiag* flag (engine/kernels/grid_params.h) for index; the
// message names the limit diag_limit(layout) gives (overloaded next to the layout).
#include <cstdint>

#include "engine/core/buffer.h"
#include "engine/core/hd.h"
#include "engine/core/types.h"
#include "engine/kernels/kernel_id.h"

namespace masav {

template <KernelId K>
struct KernelBody;  // no shared body: every backend implements the kernel itself

template <KernelId K>
concept HasKernelBody = requires {
  KernelBody<K>::kCpuGrain;
};

// The element type a body sees for a buffer of Elem, in precision F.
template <class Elem, class F>
struct BodyElem {
  using type = Elem;
};
template <class F>
struct BodyElem<Real, F> {
  using type = F;
};
template <class F>
struct BodyElem<Real4, F> {
  using type = hd::V4<F>;
};

// The pointer a body gets for each kind of buffer argument, from the backend's `data(impl)`, the
// address of a buffer's storage (Backend checked the owner): null for an absent optional one.
template <class F, class Data, class T>
const typename BodyElem<T, F>::type* body_pointer(Data&& data, const Buffer<T>& b) {
  return static_cast<const typename BodyElem<T, F>::type*>(data(b.impl()));
}
template <class F, class Data, class T>
typename BodyElem<T, F>::type* body_pointer(Data&& data, Buffer<T>& b) {
  return static_cast<typename BodyElem<T, F>::type*>(data(b.impl()));
}
template <class F, class Data, class T>
const typename BodyElem<T, F>::type* body_pointer(Data&& data, const Buffer<T>* b) {
  return b ? body_pointer<F>(data, *b) : nullptr;
}
template <class F, class Data, class T>
typename BodyElem<T, F>::type* body_pointer(Data&& data, Buffer<T>* b) {
  return b ? body_pointer<F>(data, *b) : nullptr;
}

// The limit a kernel's diagnostics name (0: none), overloaded for the layouts that have one.
template <class Layout>
uint32_t diag_limit(const Layout&) {
  return 0;
}

// The parameters a kernel's device code reads: the Params themselves, or a layout derived from
// them (and from the buffers) once on the host, overloaded next to the Params where it differs.
template <class F, class Params, class... Buffers>
const Params& device_params(const Params& p, const Buffers&...) {
  return p;
}

}  // namespace masav

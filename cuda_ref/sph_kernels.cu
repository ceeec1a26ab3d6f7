// SPH kernels on CUDA: thin wrappers around engine/kernels/sph_kernels.h, the very bodies the
// CPU reference runs. One thread per particle; neighbours are read in cell order (the arrays are
// sorted by the hash grid every rebuild), no atomics in the neighbour loops; statistics are
// reduced per warp and added with one atomic per warp.
//
// The neighbour kernels are instantiated per pressure model (as the Vulkan shaders are
// specialised on it): each copies the layout and sets its model to the constant, so the bodies'
// tests of c.model fold away with the other model's terms and registers. This file is compiled
// with -prec-div=false -prec-sqrt=false (cuda_ref/CMakeLists.txt): the divisions and square roots
// of the pair terms are the approximate ones (2 ulp, as GLSL's on NVIDIA), within the kernel
// tests' float tolerances against the fp64 CPU reference.
#include <type_traits>

#include "cuda_ref/cuda_launch.h"
#include "cuda_ref/sph_launch.h"
#include "cuda_ref/warp_reduce.cuh"
#include "engine/kernels/sph_integrate_body.h"

namespace masav::cuda::launch {
namespace {

// Four blocks of kBlock threads per multiprocessor, 64 registers (50% occupancy): density fits
// without spilling on sm_80-90, forces on sm_90 (sm_80-89: 4 bytes in wcsph), where
// sph::force_at walks the wall images apart from the direct terms. With the images inside its
// walk (cuda.sph_images_after=off) forces is bounded to three blocks (72 registers, sm_90):
// measured on an H100 (2026-11-26), 1,048,576 particles, before the image sets' loop was kept
// rolled: 95 registers unbounded (2 blocks) 0.494 ms, 80 at three blocks 0.379 ms, 64 at four
// blocks with 124 bytes spilled 0.407 ms.
constexpr int kNeighborBlocks = 4;
constexpr int kInsideBlocks = 3;

// The layout with its model fixed at compile time.
template <SphPressureModel M>
__device__ inline SphStepLayout<float> with_model(const SphStepLayout<float>& layout) {
  SphStepLayout<float> c = layout;
  c.model = M;
  return c;
}

// Every thread of the block reaches the reductions and the vote (kBlock is a multiple of 32).
// The walk comes in two copies, chosen per warp: with the wall images where a lane of the warp
// is within h of a wall, and without them elsewhere (most warps), whose loop holds no test
// for them. Both copies' pair terms are unfused (sph::unfused_mul), so they round alike and a
// particle's density does not depend on which copy its warp took: the ranks of a split run,
// whose warps hold other particles, stay bit for bit the one-process run.
template <SphPressureModel M>
__global__ void __launch_bounds__(kBlock, kNeighborBlocks)
    density_kernel(SphStepLayout<float> layout, const V4* __restrict__ pos,
                   const uint32_t* __restrict__ cells, const uint32_t* __restrict__ start,
                   const uint32_t* __restrict__ end, float* density, float* pressure,
                   uint32_t* stats, const V4* __restrict__ vel, V4* state, uint32_t* reach_rows,
                   uint32_t* neighbor_rows) {
  const SphStepLayout<float> c = with_model<M>(layout);
  const uint64_t i = c.first + particle_thread();  // the range computed: [first, end)
  const bool live = i < c.end;
  auto pos_at = [pos](uint32_t j) { return sph::xyz(pos[j]); };
  const sph::V3<float> xi = live ? pos_at(uint32_t(i)) : sph::V3<float>{0.0f, 0.0f, 0.0f};
  const sph::WallMirrors<float> mirrors =
      live && c.walls ? sph::wall_mirrors(xi, c) : sph::WallMirrors<float>{};
  const bool walls_near = __any_sync(0xffffffffu, mirrors.axes != 0u);
  uint32_t cand = 0, within = 0, over = 0, bad = 0, rho_bits = 0;
  if (live) {
    const uint32_t dims[3] = {c.dims.x, c.dims.y, c.dims.z};
    const auto masks = sph::row_masks(neighbor_rows, uint32_t(i), c.n);
    const auto reach = sph::reach_of(c, reach_rows, uint32_t(i));
    const auto r =
        walls_near
            ? sph::density_walk<float, true, true>(uint32_t(i), xi, mirrors, cells[i], dims, start,
                                                   end, c.max_candidates, c, pos_at, masks, reach)
            : sph::density_walk<float, false, true>(uint32_t(i), xi, mirrors, cells[i], dims, start,
                                                    end, c.max_candidates, c, pos_at, masks, reach);
    const float p = sph::pressure_of(r.density, c);
    density[i] = r.density;
    pressure[i] = p;
    if (state)
      sph::store_state(state, uint32_t(i), sph::make_neighbor(xi, sph::xyz(vel[i]), r.density, p));
    cand = r.candidates;
    within = r.neighbors;
    if (r.overflow) over = ~uint32_t(i);
    if (!isfinite(r.density) || !isfinite(p)) bad = ~uint32_t(i);
    // A non-negative float's bits order like the float.
    if (!bad) rho_bits = __float_as_uint(fmaxf(r.density, 0.0f));
  }
  cand = warp_max(cand);
  within = warp_max(within);
  over = warp_max(over);
  bad = warp_max(bad);
  rho_bits = warp_max(rho_bits);
  if (lane0()) {
    atomicMax(&stats[kSphStatMaxCandidates], cand);
    atomicMax(&stats[kSphStatMaxNeighbors], within);
    atomicMax(&stats[kSphStatMaxDensity], rho_bits);
    if (over) atomicMax(&stats[kSphStatOverflow], over);
    if (bad) atomicMax(&stats[kSphStatNonFinite], bad);
  }
}

// Packed: the neighbours read from sph_density's neighbour state (one 32-byte record each,
// p / rho^2 computed there) instead of from positions, velocities, density and pressure.
template <SphPressureModel M, bool ImagesAfter, bool Packed>
__global__ void __launch_bounds__(kBlock, ImagesAfter ? kNeighborBlocks : kInsideBlocks)
    forces_kernel(SphStepLayout<float> layout, const V4* __restrict__ pos,
                  const V4* __restrict__ vel, const float* __restrict__ density,
                  const float* __restrict__ pressure, const V4* __restrict__ state,
                  const uint32_t* __restrict__ cells, const uint32_t* __restrict__ start,
                  const uint32_t* __restrict__ end, V4* accel, uint32_t* stats,
                  const uint32_t* __restrict__ neighbor_rows) {
  const SphStepLayout<float> c = with_model<M>(layout);
  const uint64_t i = c.first + particle_thread();  // the range computed: [first, c.end)
  uint32_t cand = 0, over = 0, bad = 0, a2 = 0;
  if (i < c.end) {
    const uint32_t dims[3] = {c.dims.x, c.dims.y, c.dims.z};
    auto pos_at = [=](uint32_t j) {
      if constexpr (Packed)
        return sph::state_position(state, j);
      else
        return sph::xyz(pos[j]);
    };
    auto fetch = [=](uint32_t j) {
      if constexpr (Packed)
        return sph::load_state(state, j);
      else
        return sph::make_neighbor<float>(sph::xyz(pos[j]), sph::xyz(vel[j]), density[j],
                                         pressure[j]);
    };
    const V4 pw = pos[i];
    const sph::Neighbor<float> me = fetch(uint32_t(i));
    const auto r = sph::force_at<float, ImagesAfter>(
        uint32_t(i), me, cells[i], dims, start, end, c.max_candidates, c, pos_at, fetch,
        sph::row_masks(neighbor_rows, uint32_t(i), c.n));
    const sph::V3<float> a = sph::total_accel(r.accel, pw.w, c);
    accel[i] = V4{a.x, a.y, a.z, float(r.neighbors)};
    cand = r.candidates;
    if (r.overflow) over = ~uint32_t(i);
    if (!sph::finite3(a))
      bad = ~uint32_t(i);
    else if (pw.w > 0.0f)
      a2 = __float_as_uint(sph::dot(a, a));
  }
  cand = warp_max(cand);
  over = warp_max(over);
  bad = warp_max(bad);
  a2 = warp_max(a2);
  if (lane0()) {
    atomicMax(&stats[kSphStatMaxCandidates], cand);
    atomicMax(&stats[kSphStatMaxAccel2], a2);
    if (over) atomicMax(&stats[kSphStatOverflow], over);
    if (bad) atomicMax(&stats[kSphStatNonFinite], bad);
  }
}

__global__ void integrate_kernel(SphIntegrateLayout<float> p, const V4* x0, const V4* v0,
                                 const V4* vk, const V4* accel, V4* x_out, V4* v_out, V4* sum_x,
                                 V4* sum_v, uint32_t* stats) {
  const uint64_t i = p.first + particle_thread();  // the range stepped: [first, end)
  uint32_t s2 = 0, d2 = 0, bad = 0, outside = 0;
  if (i < p.end) {
    const auto r =
        sph::integrate_particle(uint32_t(i), p, x0, v0, vk, accel, x_out, v_out, sum_x, sum_v);
    if (r.non_finite) {
      bad = ~uint32_t(i);
    } else {
      s2 = __float_as_uint(r.speed2);
      d2 = __float_as_uint(r.disp2);
      outside = r.outside ? 1u : 0u;
    }
  }
  s2 = warp_max(s2);
  d2 = warp_max(d2);
  bad = warp_max(bad);
  outside = warp_sum(outside);
  if (lane0()) {
    atomicMax(&stats[kSphStatMaxSpeed2], s2);
    atomicMax(&stats[kSphStatMaxDisp2], d2);
    if (bad) atomicMax(&stats[kSphStatNonFinite], bad);
    if (outside) atomicAdd(&stats[kSphStatOutside], outside);
  }
}

// launch(std::integral_constant<SphPressureModel, M>{}) for the model m: the launch of the
// kernels instantiated for it.
template <class Launch>
cudaError_t for_model(SphPressureModel m, Launch&& launch) {
  using M = SphPressureModel;
  switch (m) {
    case M::wcsph:
      return launch(std::integral_constant<M, M::wcsph>{});
    case M::thesis:
      return launch(std::integral_constant<M, M::thesis>{});
    case M::dfsph:
      return launch(std::integral_constant<M, M::dfsph>{});
  }
  return cudaErrorInvalidValue;
}

}  // namespace

cudaError_t sph_density(cudaStream_t s, dim3 grid, const SphStepLayout<float>& c, const V4* pos,
                        const uint32_t* cells, const uint32_t* start, const uint32_t* end,
                        float* density, float* pressure, uint32_t* stats, const V4* vel, V4* state,
                        uint32_t* reach_rows, uint32_t* neighbor_rows) {
  return for_model(c.model, [&](auto m) {
    density_kernel<decltype(m)::value><<<grid, kBlock, 0, s>>>(
        c, pos, cells, start, end, density, pressure, stats, vel, state, reach_rows, neighbor_rows);
    return cudaGetLastError();
  });
}

cudaError_t sph_forces(cudaStream_t s, dim3 grid, const SphStepLayout<float>& c, const V4* pos,
                       const V4* vel, const float* density, const float* pressure, const V4* state,
                       const uint32_t* cells, const uint32_t* start, const uint32_t* end, V4* accel,
                       uint32_t* stats, const uint32_t* neighbor_rows, bool images_after) {
  return for_model(c.model, [&](auto m) {
    constexpr SphPressureModel M = decltype(m)::value;
    auto run = [&](auto kernel) {
      kernel<<<grid, kBlock, 0, s>>>(c, pos, vel, density, pressure, state, cells, start, end,
                                     accel, stats, neighbor_rows);
    };
    if (images_after)
      state ? run(forces_kernel<M, true, true>) : run(forces_kernel<M, true, false>);
    else
      state ? run(forces_kernel<M, false, true>) : run(forces_kernel<M, false, false>);
    return cudaGetLastError();
  });
}

cudaError_t sph_integrate(cudaStream_t s, dim3 grid, const SphIntegrateLayout<float>& p,
                          const V4* x0, const V4* v0, const V4* vk, const V4* accel, V4* x_out,
                          V4* v_out, V4* sum_x, V4* sum_v, uint32_t* stats) {
  integrate_kernel<<<grid, kBlock, 0, s>>>(p, x0, v0, vk, accel, x_out, v_out, sum_x, sum_v, stats);
  return cudaGetLastError();
}

}  // namespace masav::cuda::launch

// DFSPH kernels on CUDA: thin wrappers around engine/kernels/dfsph_kernels.h, the very bodies the
// CPU reference runs, over the 27-cell walk (or sph_density's neighbour row masks). One thread
// per particle, no atomics in the neighbour loops; statistics and residual sums are reduced per
// warp and added with one atomic per warp.
#include "cuda_ref/cuda_launch.h"
#include "cuda_ref/dfsph_launch.h"
#include "cuda_ref/warp_reduce.cuh"
#include "engine/kernels/dfsph_kernels.h"

namespace masav::cuda::launch {
namespace {

using V4 = hd::V4<float>;

// The candidate walk of sorted particle i (sph::walk_candidates); sets `overflow`.
struct GridWalk {
  const DfsphLayout<float>& c;
  const uint32_t* cells;
  const uint32_t* start;
  const uint32_t* end;
  const uint32_t* neighbor_rows;
  uint32_t i;
  bool* overflow;
  template <class Visit>
  __device__ void operator()(Visit&& visit) const {
    const uint32_t dims[3] = {c.dims.x, c.dims.y, c.dims.z};
    sph::walk_candidates(cells[i], dims, start, end, c.max_candidates,
                         sph::row_masks(neighbor_rows, i, c.n), *overflow, visit);
  }
};

__global__ void factor_kernel(DfsphLayout<float> c, const V4* __restrict__ pos,
                              const uint32_t* __restrict__ cells,
                              const uint32_t* __restrict__ start, const uint32_t* __restrict__ end,
                              float* factor, uint32_t* stats,
                              const uint32_t* __restrict__ neighbor_rows) {
  const uint64_t i = c.begin + particle_thread();  // the range computed: [begin, end)
  uint32_t over = 0, bad = 0;
  if (i < c.end) {
    bool overflow = false;
    auto pos_at = [pos](uint32_t j) { return sph::xyz(pos[j]); };
    const float f = sph::dfsph_factor_of<float>(
        uint32_t(i), pos_at(uint32_t(i)), c,
        GridWalk{c, cells, start, end, neighbor_rows, uint32_t(i), &overflow}, pos_at);
    factor[i] = f;
    if (overflow) over = ~uint32_t(i);
    if (!isfinite(f)) bad = ~uint32_t(i);
  }
  over = warp_max(over);
  bad = warp_max(bad);
  if (lane0()) {
    if (over) atomicMax(&stats[kSphStatOverflow], over);
    if (bad) atomicMax(&stats[kSphStatNonFinite], bad);
  }
}

__global__ void rate_kernel(DfsphLayout<float> c, const V4* __restrict__ pos,
                            const V4* __restrict__ vel, const float* __restrict__ density,
                            const float* __restrict__ factor, const uint32_t* __restrict__ cells,
                            const uint32_t* __restrict__ start, const uint32_t* __restrict__ end,
                            float* kappa, float* kappa_sum, uint32_t* residual,
                            const uint32_t* __restrict__ neighbor_rows) {
  if (sph::dfsph_stopped(c, residual))
    return;  // every thread alike: the iteration before converged
  const uint64_t i = c.begin + particle_thread();  // the range computed: [begin, end)
  uint32_t units = 0;
  if (i < c.end) {
    bool overflow = false;
    auto pos_at = [pos](uint32_t j) { return sph::xyz(pos[j]); };
    auto vel_at = [vel](uint32_t j) { return sph::xyz(vel[j]); };
    const V4 pw = pos[i];
    const auto r = sph::dfsph_rate_of<float>(
        uint32_t(i), sph::xyz(pw), sph::xyz(vel[i]), density[i], factor[i], c,
        GridWalk{c, cells, start, end, neighbor_rows, uint32_t(i), &overflow}, pos_at, vel_at);
    kappa[i] = r.kappa;
    kappa_sum[i] = sph::dfsph_kappa_sum(kappa_sum[i], r.kappa, c);
    if (pw.w > 0.0f) units = sph::dfsph_residual_units(r.residual);
  }
  units = warp_sum(units);  // at most 32 x 2^24: fits
  if (lane0() && units) {
    uint32_t* words = residual + 2 * c.slot;
    const uint32_t old = atomicAdd(&words[0], units);
    if (old > 0xffffffffu - units) atomicAdd(&words[1], 1u);  // the low word wrapped
  }
}

__global__ void correct_kernel(DfsphLayout<float> c, const V4* __restrict__ pos,
                               const float* __restrict__ kappa, const uint32_t* __restrict__ cells,
                               const uint32_t* __restrict__ start, const uint32_t* __restrict__ end,
                               V4* vel, uint32_t* stats, const uint32_t* __restrict__ residual,
                               const uint32_t* __restrict__ neighbor_rows) {
  if (residual && sph::dfsph_stopped(c, residual)) return;  // as rate_kernel
  const uint64_t i = c.begin + particle_thread();           // the range computed: [begin, end)
  uint32_t bad = 0, s2 = 0;
  if (i < c.end) {
    const V4 pw = pos[i];
    if (pw.w > 0.0f) {
      bool overflow = false;
      auto pos_at = [pos](uint32_t j) { return sph::xyz(pos[j]); };
      auto kappa_at = [kappa](uint32_t j) { return kappa[j]; };
      const sph::V3<float> dv = sph::dfsph_correction_of<float>(
          uint32_t(i), sph::xyz(pw), kappa[i], c,
          GridWalk{c, cells, start, end, neighbor_rows, uint32_t(i), &overflow}, pos_at, kappa_at);
      const V4 v0 = vel[i];
      const sph::V3<float> v = sph::xyz(v0) + pw.w * dv;
      vel[i] = V4{v.x, v.y, v.z, v0.w};
      if (!sph::finite3(v))
        bad = ~uint32_t(i);
      else
        s2 = __float_as_uint(sph::dot(v, v));
    }
  }
  bad = warp_max(bad);
  s2 = warp_max(s2);
  if (lane0()) {
    atomicMax(&stats[kSphStatMaxSpeed2], s2);
    if (bad) atomicMax(&stats[kSphStatNonFinite], bad);
  }
}

}  // namespace

cudaError_t dfsph_factor(cudaStream_t s, dim3 grid, const DfsphLayout<float>& c, const V4* pos,
                         const uint32_t* cells, const uint32_t* start, const uint32_t* end,
                         float* factor, uint32_t* stats, const uint32_t* neighbor_rows) {
  factor_kernel<<<grid, kBlock, 0, s>>>(c, pos, cells, start, end, factor, stats, neighbor_rows);
  return cudaGetLastError();
}

cudaError_t dfsph_rate(cudaStream_t s, dim3 grid, const DfsphLayout<float>& c, const V4* pos,
                       const V4* vel, const float* density, const float* factor,
                       const uint32_t* cells, const uint32_t* start, const uint32_t* end,
                       float* kappa, float* kappa_sum, uint32_t* residual,
                       const uint32_t* neighbor_rows) {
  rate_kernel<<<grid, kBlock, 0, s>>>(c, pos, vel, density, factor, cells, start, end, kappa,
                                      kappa_sum, residual, neighbor_rows);
  return cudaGetLastError();
}

cudaError_t dfsph_correct(cudaStream_t s, dim3 grid, const DfsphLayout<float>& c, const V4* pos,
                          const float* kappa, const uint32_t* cells, const uint32_t* start,
                          const uint32_t* end, V4* vel, uint32_t* stats, const uint32_t* residual,
                          const uint32_t* neighbor_rows) {
  correct_kernel<<<grid, kBlock, 0, s>>>(c, pos, kappa, cells, start, end, vel, stats, residual,
                                         neighbor_rows);
  return cudaGetLastError();
}

}  // namespace masav::cuda::launch

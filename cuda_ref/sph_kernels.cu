// SPH kernels on CUDA: thin wrappers around engine/kernels/sph_kernels.h, the very bodies the
// CPU reference runs. One thread per particle; neighbours are read in cell order (the arrays are
// sorted by the hash grid every rebuild), no atomics in the neighbour loops; statistics are
// reduced per warp and added with one atomic per warp.
#include "cuda_ref/cuda_launch.h"
#include "cuda_ref/sph_launch.h"
#include "engine/sph/sph_kernel_params.h"

namespace masav::cuda::launch {
namespace {

using V = sph::V3<float>;

__device__ uint64_t sph_thread() {
  return (uint64_t(blockIdx.y) * gridDim.x + blockIdx.x) * blockDim.x + threadIdx.x;
}

__device__ uint32_t warp_max(uint32_t v) {
  for (int o = 16; o > 0; o >>= 1) v = max(v, __shfl_xor_sync(0xffffffffu, v, o));
  return v;
}
__device__ uint32_t warp_sum(uint32_t v) {
  for (int o = 16; o > 0; o >>= 1) v += __shfl_xor_sync(0xffffffffu, v, o);
  return v;
}
__device__ bool lane0() {
  return (threadIdx.x & 31u) == 0u;
}

__device__ V xyz(float4 q) {
  return V{q.x, q.y, q.z};
}
__device__ bool finite3(V v) {
  return isfinite(v.x) && isfinite(v.y) && isfinite(v.z);
}

// Every thread of the block reaches the reductions (kBlock is a multiple of 32).
__global__ void density_kernel(SphGridArgs g, sph::Coefficients<float> c,
                               const float4* __restrict__ pos, const uint32_t* __restrict__ cells,
                               const uint32_t* __restrict__ start, const uint32_t* __restrict__ end,
                               float* density, float* pressure, uint32_t* stats) {
  const uint64_t i = sph_thread();
  uint32_t cand = 0, within = 0, over = 0, bad = 0;
  if (i < g.n) {
    auto pos_at = [pos](uint32_t j) { return xyz(__ldg(&pos[j])); };
    const auto r = sph::density_at<float>(pos_at(uint32_t(i)), cells[i], g.dims, start, end,
                                          g.max_candidates, c, pos_at);
    const float p = sph::pressure_of(r.density, c);
    density[i] = r.density;
    pressure[i] = p;
    cand = r.candidates;
    within = r.neighbors;
    if (r.overflow) over = ~uint32_t(i);
    if (!isfinite(r.density) || !isfinite(p)) bad = ~uint32_t(i);
  }
  cand = warp_max(cand);
  within = warp_max(within);
  over = warp_max(over);
  bad = warp_max(bad);
  if (lane0()) {
    atomicMax(&stats[kSphStatMaxCandidates], cand);
    atomicMax(&stats[kSphStatMaxNeighbors], within);
    if (over) atomicMax(&stats[kSphStatOverflow], over);
    if (bad) atomicMax(&stats[kSphStatNonFinite], bad);
  }
}

__global__ void forces_kernel(SphGridArgs g, sph::Coefficients<float> c,
                              const float4* __restrict__ pos, const float4* __restrict__ vel,
                              const float* __restrict__ density, const float* __restrict__ pressure,
                              const uint32_t* __restrict__ cells,
                              const uint32_t* __restrict__ start, const uint32_t* __restrict__ end,
                              float4* accel, uint32_t* stats) {
  const uint64_t i = sph_thread();
  uint32_t cand = 0, over = 0, bad = 0, a2 = 0;
  if (i < g.n) {
    auto pos_at = [pos](uint32_t j) { return xyz(__ldg(&pos[j])); };
    auto fetch = [=](uint32_t j) {
      return sph::make_neighbor<float>(xyz(__ldg(&pos[j])), xyz(__ldg(&vel[j])),
                                       __ldg(&density[j]), __ldg(&pressure[j]));
    };
    const float4 pw = pos[i];
    const sph::Neighbor<float> me = fetch(uint32_t(i));
    const auto r = sph::force_at<float>(uint32_t(i), me, cells[i], g.dims, start, end,
                                        g.max_candidates, c, pos_at, fetch);
    const V a = sph::total_accel(r.accel, pw.w, c);
    accel[i] = make_float4(a.x, a.y, a.z, float(r.neighbors));
    cand = r.candidates;
    if (r.overflow) over = ~uint32_t(i);
    if (!finite3(a))
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

__global__ void integrate_kernel(SphIntegrateArgs args, const float4* x0, const float4* v0,
                                 const float4* vk, const float4* accel, float4* x_out,
                                 float4* v_out, float4* sum_x, float4* sum_v, uint32_t* stats) {
  const uint64_t i = sph_thread();
  const uint32_t op = args.stage.op;
  const bool kick = op == sph::kOpKick;
  const bool rk4 = op >= sph::kOpRk4Stage1 && op <= sph::kOpRk4Final;
  uint32_t s2 = 0, d2 = 0, bad = 0, outside = 0;
  if (i < args.n) {
    const float4 xw = kick ? make_float4(0, 0, 0, 0) : x0[i];
    const V x = xyz(xw), v = xyz(v0[i]);
    const V kv = vk ? xyz(vk[i]) : v;
    const V a = xyz(accel[i]);
    V sx = rk4 ? xyz(sum_x[i]) : V{0, 0, 0};
    V sv = rk4 ? xyz(sum_v[i]) : V{0, 0, 0};
    V xn{}, vn{};
    const bool inside = sph::stage_particle(args.stage, x, v, kv, a, xn, vn, sx, sv);
    if (!kick) x_out[i] = make_float4(xn.x, xn.y, xn.z, xw.w);
    v_out[i] = make_float4(vn.x, vn.y, vn.z, 0.0f);
    if (rk4) sum_x[i] = make_float4(sx.x, sx.y, sx.z, 0.0f);
    if (rk4 || op == sph::kOpKickDrift) sum_v[i] = make_float4(sv.x, sv.y, sv.z, 0.0f);
    if (!finite3(vn) || (!kick && !finite3(xn))) {
      bad = ~uint32_t(i);
    } else {
      s2 = __float_as_uint(sph::dot(vn, vn));
      if (!kick) {
        const V d = xn - x;
        d2 = __float_as_uint(sph::dot(d, d));
        outside = sph::op_ends_step(op) && !inside ? 1u : 0u;
      }
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

}  // namespace

cudaError_t sph_density(cudaStream_t s, dim3 grid, SphGridArgs g, sph::Coefficients<float> c,
                        const float4* pos, const uint32_t* cells, const uint32_t* start,
                        const uint32_t* end, float* density, float* pressure, uint32_t* stats) {
  density_kernel<<<grid, kBlock, 0, s>>>(g, c, pos, cells, start, end, density, pressure, stats);
  return cudaGetLastError();
}

cudaError_t sph_forces(cudaStream_t s, dim3 grid, SphGridArgs g, sph::Coefficients<float> c,
                       const float4* pos, const float4* vel, const float* density,
                       const float* pressure, const uint32_t* cells, const uint32_t* start,
                       const uint32_t* end, float4* accel, uint32_t* stats) {
  forces_kernel<<<grid, kBlock, 0, s>>>(g, c, pos, vel, density, pressure, cells, start, end, accel,
                                        stats);
  return cudaGetLastError();
}

cudaError_t sph_integrate(cudaStream_t s, dim3 grid, SphIntegrateArgs a, const float4* x0,
                          const float4* v0, const float4* vk, const float4* accel, float4* x_out,
                          float4* v_out, float4* sum_x, float4* sum_v, uint32_t* stats) {
  integrate_kernel<<<grid, kBlock, 0, s>>>(a, x0, v0, vk, accel, x_out, v_out, sum_x, sum_v, stats);
  return cudaGetLastError();
}

}  // namespace masav::cuda::launch

// SPH kernels on CUDA, host side: checks, fp32 coefficients computed once, then the launches in
// sph_kernels.cu.
#include "cuda_ref/cuda_backend.h"
#include "cuda_ref/cuda_check.h"
#include "cuda_ref/sph_launch.h"
#include "engine/sph/sph_coefficients.h"

namespace masav::cuda {
namespace {

launch::SphGridArgs grid_args(const SphStepParams& p) {
  return launch::SphGridArgs{{p.grid.dims.x, p.grid.dims.y, p.grid.dims.z}, p.n, p.max_candidates};
}

}  // namespace

void CudaBackend::do_sph_density(const SphStepParams& p, uint64_t, const Buffer<Real4>& positions,
    const Buffer<uint32_t>& cells, const Buffer<uint32_t>& cell_start,
    const Buffer<uint32_t>& cell_end, Buffer<Real>& density, Buffer<Real>& pressure,
    Buffer<uint32_t>& stats) {
  const SphDensityIO io{&positions, {&cells, &cell_start, &cell_end}, &density, &pressure, &stats};
  const char* k = "sph_density";
  check(launch::sph_density(stream_, grid_for_items(p.n, k), grid_args(p),
                            to_float(make_coefficients(p)),
                            static_cast<const float4*>(ptr(io.positions->impl(), k)),
                            static_cast<const uint32_t*>(ptr(io.grid.cells->impl(), k)),
                            static_cast<const uint32_t*>(ptr(io.grid.cell_start->impl(), k)),
                            static_cast<const uint32_t*>(ptr(io.grid.cell_end->impl(), k)),
                            static_cast<float*>(ptr(io.density->impl(), k)),
                            static_cast<float*>(ptr(io.pressure->impl(), k)),
                            static_cast<uint32_t*>(ptr(io.stats->impl(), k))),
        k, "launch");
}

void CudaBackend::do_sph_forces(const SphStepParams& p, uint64_t, const Buffer<Real4>& positions,
    const Buffer<Real4>& velocities, const Buffer<Real>& density, const Buffer<Real>& pressure,
    const Buffer<uint32_t>& cells, const Buffer<uint32_t>& cell_start,
    const Buffer<uint32_t>& cell_end, Buffer<Real4>& accel, Buffer<uint32_t>& stats) {
  const SphForcesIO io{&positions, &velocities, &density, &pressure,
                       {&cells, &cell_start, &cell_end}, &accel, &stats};
  const char* k = "sph_forces";
  check(launch::sph_forces(stream_, grid_for_items(p.n, k), grid_args(p),
                           to_float(make_coefficients(p)),
                           static_cast<const float4*>(ptr(io.positions->impl(), k)),
                           static_cast<const float4*>(ptr(io.velocities->impl(), k)),
                           static_cast<const float*>(ptr(io.density->impl(), k)),
                           static_cast<const float*>(ptr(io.pressure->impl(), k)),
                           static_cast<const uint32_t*>(ptr(io.grid.cells->impl(), k)),
                           static_cast<const uint32_t*>(ptr(io.grid.cell_start->impl(), k)),
                           static_cast<const uint32_t*>(ptr(io.grid.cell_end->impl(), k)),
                           static_cast<float4*>(ptr(io.accel->impl(), k)),
                           static_cast<uint32_t*>(ptr(io.stats->impl(), k))),
        k, "launch");
}

void CudaBackend::do_sph_integrate(const SphIntegrateParams& p, uint64_t, const Buffer<Real4>* x0,
    const Buffer<Real4>& v0, const Buffer<Real4>* vk, const Buffer<Real4>& accel,
    Buffer<Real4>* x_out, Buffer<Real4>& v_out, Buffer<Real4>* sum_x, Buffer<Real4>* sum_v,
    Buffer<uint32_t>& stats) {
  const SphIntegrateIO io{x0, &v0, vk, &accel, x_out, &v_out, sum_x, sum_v, &stats};
  const char* k = "sph_integrate";
  auto f4 = [&](const Buffer<Real4>* b) {
    return b ? static_cast<float4*>(ptr(b->impl(), k)) : nullptr;
  };
  launch::SphIntegrateArgs a{};
  a.stage.op = uint32_t(p.op);
  a.stage.dt = float(p.dt);
  a.stage.walls = p.walls ? 1u : 0u;
  a.stage.lo[0] = float(p.box_min.x);
  a.stage.lo[1] = float(p.box_min.y);
  a.stage.lo[2] = float(p.box_min.z);
  a.stage.hi[0] = float(p.box_max.x);
  a.stage.hi[1] = float(p.box_max.y);
  a.stage.hi[2] = float(p.box_max.z);
  a.stage.restitution = float(p.restitution);
  a.stage.tangential_damping = float(p.tangential_damping);
  a.n = p.n;
  const bool kick = p.op == SphStageOp::kick;
  check(launch::sph_integrate(stream_, grid_for_items(p.n, k), a, kick ? nullptr : f4(io.x0),
                              f4(io.v0), f4(io.vk), f4(io.accel), kick ? nullptr : f4(io.x_out),
                              f4(io.v_out), f4(io.sum_x), f4(io.sum_v),
                              static_cast<uint32_t*>(ptr(io.stats->impl(), k))),
        k, "launch");
}

}  // namespace masav::cuda

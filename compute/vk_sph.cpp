// SPH kernels on Vulkan: parameter checks, push constants (fp32 coefficients computed once on
// the host) and dispatches of sph_density, sph_forces and sph_integrate, one invocation per
// particle.
#include <fmt/format.h>

#include "compute/vk_backend.h"
#include "engine/core/error.h"
#include "engine/sph/sph_coefficients.h"

namespace masav::vk {
namespace {

struct SphCoefsPush {
  float h2, inv_h, inv_h2, density;
  float pressure, viscosity, rest_density, inv_rest_density;
  float eos, gx, gy, gz;
  uint32_t model, clamp_negative, max_candidates, walls;
  float lo[4], hi[4];
};
struct SphStepPush {
  float origin_inv_cell[4];
  uint32_t dims_n[4];
  SphCoefsPush c;
};
static_assert(sizeof(SphStepPush) == 128, "matches the GLSL push block (the guaranteed size)");

struct SphIntegratePush {
  float lo_dt[4];
  float hi_restitution[4];
  float tangential_damping;
  uint32_t op, walls, n, use_vk;
};
static_assert(sizeof(SphIntegratePush) == 52, "matches the GLSL push block");

SphStepPush step_push(const SphStepParams& p) {
  const sph::Coefficients<float> f = to_float(make_coefficients(p));
  const GridParams& g = p.grid;
  return SphStepPush{{g.origin.x, g.origin.y, g.origin.z, g.inv_cell},
                     {g.dims.x, g.dims.y, g.dims.z, p.n},
                     {f.h2,
                      f.inv_h,
                      f.inv_h2,
                      f.density,
                      f.pressure,
                      f.viscosity,
                      f.rest_density,
                      f.inv_rest_density,
                      f.eos,
                      f.gravity[0],
                      f.gravity[1],
                      f.gravity[2],
                      f.model,
                      f.clamp_negative_pressure,
                      p.max_candidates,
                      f.walls,
                      {f.lo[0], f.lo[1], f.lo[2], f.wall_viscosity},
                      {f.hi[0], f.hi[1], f.hi[2], f.wall_offset}}};
}

uint64_t groups_for(uint64_t items, uint32_t wg) {
  return (items + wg - 1) / wg;
}

}  // namespace

void VulkanBackend::do_sph_density(const SphStepParams& p, uint64_t, const Buffer<Real4>& positions,
    const Buffer<uint32_t>& cells, const Buffer<uint32_t>& cell_start,
    const Buffer<uint32_t>& cell_end, Buffer<Real>& density, Buffer<Real>& pressure,
    Buffer<uint32_t>& stats) {
  const SphDensityIO io{&positions, {&cells, &cell_start, &cell_end}, &density, &pressure, &stats};
  const char* k = "sph_density";
  const SphStepPush push = step_push(p);
  run({"sph_density", 7, sizeof push, {}},
      {alloc(io.positions->impl(), k), alloc(io.grid.cells->impl(), k),
       alloc(io.grid.cell_start->impl(), k), alloc(io.grid.cell_end->impl(), k),
       alloc(io.density->impl(), k), alloc(io.pressure->impl(), k), alloc(io.stats->impl(), k)},
      &push, groups_for(p.n, options_.workgroup_size));
}

void VulkanBackend::do_sph_forces(const SphStepParams& p, uint64_t, const Buffer<Real4>& positions,
    const Buffer<Real4>& velocities, const Buffer<Real>& density, const Buffer<Real>& pressure,
    const Buffer<uint32_t>& cells, const Buffer<uint32_t>& cell_start,
    const Buffer<uint32_t>& cell_end, Buffer<Real4>& accel, Buffer<uint32_t>& stats) {
  const SphForcesIO io{&positions, &velocities, &density, &pressure,
                       {&cells, &cell_start, &cell_end}, &accel, &stats};
  const char* k = "sph_forces";
  const SphStepPush push = step_push(p);
  run({"sph_forces", 9, sizeof push, {}},
      {alloc(io.positions->impl(), k), alloc(io.velocities->impl(), k),
       alloc(io.density->impl(), k), alloc(io.pressure->impl(), k), alloc(io.grid.cells->impl(), k),
       alloc(io.grid.cell_start->impl(), k), alloc(io.grid.cell_end->impl(), k),
       alloc(io.accel->impl(), k), alloc(io.stats->impl(), k)},
      &push, groups_for(p.n, options_.workgroup_size));
}

void VulkanBackend::do_sph_integrate(const SphIntegrateParams& p, uint64_t, const Buffer<Real4>* x0,
    const Buffer<Real4>& v0, const Buffer<Real4>* vk, const Buffer<Real4>& accel,
    Buffer<Real4>* x_out, Buffer<Real4>& v_out, Buffer<Real4>* sum_x, Buffer<Real4>* sum_v,
    Buffer<uint32_t>& stats) {
  const SphIntegrateIO io{x0, &v0, vk, &accel, x_out, &v_out, sum_x, sum_v, &stats};
  const char* k = "sph_integrate";
  const SphIntegratePush push{
      {float(p.box_min.x), float(p.box_min.y), float(p.box_min.z), float(p.dt)},
      {float(p.box_max.x), float(p.box_max.y), float(p.box_max.z), float(p.restitution)},
      float(p.tangential_damping),
      uint32_t(p.op),
      p.walls ? 1u : 0u,
      p.n,
      io.vk ? 1u : 0u};
  // Bindings the op does not read or write get a buffer it does use (never accessed).
  const auto& v0_alloc = alloc(io.v0->impl(), k);
  auto or_v0 = [&](const BufferImpl* b) { return b ? alloc(*b, k) : v0_alloc; };
  run({"sph_integrate", 9, sizeof push, {}},
      {or_v0(io.x0 ? &io.x0->impl() : nullptr), v0_alloc, or_v0(io.vk ? &io.vk->impl() : nullptr),
       alloc(io.accel->impl(), k), or_v0(io.x_out ? &io.x_out->impl() : nullptr),
       alloc(io.v_out->impl(), k), or_v0(io.sum_x ? &io.sum_x->impl() : nullptr),
       or_v0(io.sum_v ? &io.sum_v->impl() : nullptr), alloc(io.stats->impl(), k)},
      &push, groups_for(p.n, options_.workgroup_size));
}

}  // namespace masav::vk

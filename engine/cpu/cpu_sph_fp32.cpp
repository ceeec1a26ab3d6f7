// sph_forces of the CPU backend's fp32 path (CpuTuning::sph_precision = fp32): the pair terms
// of sph::force_at in single precision, 16 neighbours at a time (cpu_sph_simd.h), over the
// neighbour lists sph_density found in fp32. The inputs are rounded to fp32 once per call, as a
// GPU holds them; the acceleration is stored back in the fp64 buffers the integrator reads.
// Per particle: the neighbours and their wall images (lane by lane), then its own images (the
// shared body).
#include <algorithm>
#include <cmath>
#include <vector>

#include "engine/cpu/cpu_backend.h"
#include "engine/cpu/cpu_sph_stats.h"
#include "engine/kernels/sph_kernels.h"

namespace masav::cpu {

void CpuBackend::sph_forces_fp32(const KernelArgs<KernelId::sph_forces>& a) {
  // neighbor_rows is not read, as in the fp64 path: the lists are sph_density's. The fields
  // come from sph_density's neighbour state where given (the same values as the arrays').
  const SphStepParams& p = a.p;
  const auto c = device_params<float>(p);
  const auto [pos, vel, rho, pr, acc_out, words, state] = sph_force_buffers(a);

  // The neighbour fields, a row of 8 floats per particle (SimdPairFields).
  sph_fields_.resize(kFieldCount * std::max<size_t>(p.n, 1));
  float* fb = sph_fields_.data();
  const SimdPairFields f{fb};
  pool_.parallel_for(p.n, 8192, [&](size_t b, size_t e) {
    for (size_t i = b; i < e; ++i) {
      const sph::Neighbor<double> o =
          state ? sph::load_state(state, uint32_t(i))
                : sph::Neighbor<double>{{pos[4 * i], pos[4 * i + 1], pos[4 * i + 2]},
                                        {vel[4 * i], vel[4 * i + 1], vel[4 * i + 2]},
                                        rho[i],
                                        sph::pressure_over_rho2(pr[i], rho[i])};
      const double fields[kFieldCount] = {o.x.x, o.x.y, o.x.z, o.v.x, o.v.y, o.v.z, o.rho,
                                          o.p_rho2};
      for (size_t d = 0; d < kFieldCount; ++d) fb[kFieldCount * i + d] = float(fields[d]);
    }
  });
  // dfsph: viscosity only (sph::pair_accel), its pressure the solves' (reported, never a force).
  const SimdPairConstants sc{c.h2,
                             c.inv_h,
                             c.inv_h2,
                             c.pressure,
                             c.viscosity,
                             c.model == SphPressureModel::thesis ? 1u : 0u,
                             c.model == SphPressureModel::dfsph ? 1u : 0u};

  const size_t chunks = sph_chunks(sph_range_count(p));
  std::vector<ChunkStats> st(chunks);
  pool_.run_chunks(sph_range_count(p), chunks, [&](size_t chunk, size_t b, size_t e) {
    b += p.first;
    e += p.first;
    ChunkStats& s = st[chunk];
    for (size_t i = b; i < e; ++i) {
      const uint32_t self = uint32_t(i);
      const float* row = fb + kFieldCount * i;
      const SimdParticle me{row[kFieldX],  row[kFieldY],  row[kFieldZ],   row[kFieldVx],
                            row[kFieldVy], row[kFieldVz], row[kFieldRho], row[kFieldPRho2]};
      const uint32_t* list = sph_lists_.list(self);
      const uint32_t count = sph_lists_.count(self);
      const sph::V3<float> xi{me.x, me.y, me.z};
      const auto mirrors = c.walls ? sph::wall_mirrors(xi, c) : sph::WallMirrors<float>{};
      float sum[3];
      sph_simd_->pair_sum(f, me, list, count, sc, mirrors.axes, mirrors.plane, sum);
      sph::V3<float> acc{sum[0], sum[1], sum[2]};
      if (mirrors.axes) {
        const sph::Neighbor<float> mine{xi, {me.vx, me.vy, me.vz}, me.rho, me.p_rho2};
        acc = acc + sph::wall_image_accel(mine, mine, mirrors, c);
      }
      const float inv_mass = float(pos[4 * i + 3]);
      const sph::V3<float> acc_i = sph::total_accel(acc, inv_mass, c);
      acc_out[4 * i] = double(acc_i.x);
      acc_out[4 * i + 1] = double(acc_i.y);
      acc_out[4 * i + 2] = double(acc_i.z);
      acc_out[4 * i + 3] = double(count);
      const bool finite =
          std::isfinite(acc_i.x) && std::isfinite(acc_i.y) && std::isfinite(acc_i.z);
      add_force_stats(s, sph_lists_, self, finite, inv_mass > 0,
                      double(sph::dot(acc_i, acc_i)));
    }
  });
  merge_sph_stats(words, st);
}

}  // namespace masav::cpu

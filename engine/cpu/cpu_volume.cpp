// Voxelization, brick ranges and ray casting on the CPU reference (double precision).
#include <algorithm>
#include <vector>

#include "engine/atom/atom_checks.h"
#include "engine/kernels/volume_math.h"
#include "engine/cpu/cpu_backend.h"
#include "engine/kernels/grid_cell.h"

namespace masav::cpu {

void CpuBackend::do_voxelize(const VoxelizeParams& p, uint64_t, const Buffer<Real4>& positions,
                          const Buffer<Real>& light, Buffer<Real>& probability,
                          Buffer<Real>& mean_light, Buffer<Real>& sample) {
  const auto* pos = own(positions.impl(), "voxelize").as<double>();
  const auto* lit = own(light.impl(), "voxelize").as<double>();
  auto* prob = own(probability.impl(), "voxelize").as<double>();
  auto* mean = own(mean_light.impl(), "voxelize").as<double>();
  auto* smp = own(sample.impl(), "voxelize").as<double>();
  const size_t cells = grid_cell_count(p.grid);
  std::vector<uint32_t> count(cells, 0);
  std::vector<double> sum(cells, 0.0);
  const float origin[3] = {p.grid.origin.x, p.grid.origin.y, p.grid.origin.z};
  const uint32_t dims[3] = {p.grid.dims.x, p.grid.dims.y, p.grid.dims.z};
  // Cells from the fp32 positions, by the hash grid's rule: identical on every backend.
  for (size_t i = 0; i < p.grid.n; ++i) {
    const grid::CellCoord c = grid::point_cell(float(pos[4 * i]), float(pos[4 * i + 1]),
                                               float(pos[4 * i + 2]), origin, p.grid.inv_cell, dims);
    const uint32_t id = grid::cell_id(c.x, c.y, c.z, dims[1], dims[2]);
    ++count[id];
    sum[id] += std::min(1.0, std::max(0.0, lit[i] * double(p.light_to_unit)));
  }
  const uint32_t max_count = *std::max_element(count.begin(), count.end());
  const double inv_n = 1.0 / double(p.grid.n);
  for (size_t o = 0; o < cells; ++o) {  // output o is x fastest; the grid's cell id z fastest
    const size_t x = o % dims[0], y = o / dims[0] % dims[1], z = o / (size_t(dims[0]) * dims[1]);
    const size_t c = (x * dims[1] + y) * dims[2] + z;
    prob[o] = double(count[c]) * inv_n;
    mean[o] = count[c] ? sum[c] / double(count[c]) : 0.0;
    smp[o] = double(p.s) * mean[o] + double(p.t) * double(count[c]) / double(max_count);
  }
}

void CpuBackend::do_volume_bricks(const VolumeBrickParams& p, uint64_t, const Buffer<Real>& volume,
                               const Buffer<Real4>& tf, Buffer<Real4>& bricks) {
  const auto* vol = own(volume.impl(), "volume_bricks").as<double>();
  const auto* t = own(tf.impl(), "volume_bricks").as<double>();
  auto* out = own(bricks.impl(), "volume_bricks").as<double>();
  const UVec3 nb = brick_dims(p.volume, p.brick);
  const UVec3 d = p.volume.dims;
  const double scale = 1.0 / (double(p.volume.value_max) - p.volume.value_min);
  pool_.parallel_for(size_t(nb.x) * nb.y * nb.z, 16, [&](size_t b, size_t e) {
    for (size_t id = b; id < e; ++id) {
      const uint32_t bx = uint32_t(id % nb.x), by = uint32_t(id / nb.x % nb.y),
                     bz = uint32_t(id / (size_t(nb.x) * nb.y));
      double lo = 1e300, hi = -1e300;
      for (uint32_t k = bz * p.brick; k <= std::min((bz + 1) * p.brick, d.z - 1); ++k)
        for (uint32_t j = by * p.brick; j <= std::min((by + 1) * p.brick, d.y - 1); ++j)
          for (uint32_t i = bx * p.brick; i <= std::min((bx + 1) * p.brick, d.x - 1); ++i) {
            const double v = vol[(size_t(k) * d.y + j) * d.x + i];
            lo = std::min(lo, v);
            hi = std::max(hi, v);
          }
      // Largest alpha of the entries whose linear pieces cover [lo, hi] after normalisation.
      const double nlo = std::clamp((lo - p.volume.value_min) * scale, 0.0, 1.0);
      const double nhi = std::clamp((hi - p.volume.value_min) * scale, 0.0, 1.0);
      const uint32_t k0 = uint32_t(nlo * (p.tf_size - 1));
      const uint32_t k1 = std::min<uint32_t>(uint32_t(std::ceil(nhi * (p.tf_size - 1))), p.tf_size - 1);
      double amax = 0;
      for (uint32_t k = k0; k <= k1; ++k) amax = std::max(amax, t[4 * k + 3]);
      out[4 * id] = lo;
      out[4 * id + 1] = hi;
      out[4 * id + 2] = amax;
      out[4 * id + 3] = 0.0;
    }
  });
}

void CpuBackend::do_raymarch(const RaymarchParams& p, uint64_t, const Buffer<Real>& volume,
                          const Buffer<Real4>& tf, const Buffer<Real4>& bricks,
                          Buffer<Real4>& image) {
  const auto* vol = own(volume.impl(), "raymarch").as<double>();
  const auto* t = own(tf.impl(), "raymarch").as<double>();
  const auto* br = own(bricks.impl(), "raymarch").as<double>();
  auto* out = own(image.impl(), "raymarch").as<double>();
  const volume::RayCamera cam = make_ray_camera(p);
  const UVec3 d = p.volume.dims;
  auto vat = [&](uint32_t i, uint32_t j, uint32_t k) { return vol[(size_t(k) * d.y + j) * d.x + i]; };
  auto tat = [&](uint32_t k) {
    return volume::V4<double>{t[4 * k], t[4 * k + 1], t[4 * k + 2], t[4 * k + 3]};
  };
  auto bat = [&](uint32_t x, uint32_t y, uint32_t z) {
    return br[4 * ((size_t(z) * cam.bricks[1] + y) * cam.bricks[0] + x) + 2];
  };
  pool_.parallel_for(size_t(p.width) * p.height, 256, [&](size_t b, size_t e) {
    for (size_t px = b; px < e; ++px) {
      const auto c = volume::raymarch_pixel<double>(p, cam, uint32_t(px % p.width),
                                                    uint32_t(px / p.width), vat, tat, bat);
      out[4 * px] = c.r;
      out[4 * px + 1] = c.g;
      out[4 * px + 2] = c.b;
      out[4 * px + 3] = c.a;
    }
  });
}

}  // namespace masav::cpu

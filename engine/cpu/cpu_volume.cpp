// Voxelization on the CPU reference (double precision), and the fp32 render path of the raymarch
// (CpuRenderPrecision::fp32: several rays at a time, cpu_raymarch_lanes.h, where the compositing
// allows it, else the shared body per pixel); the fp64 raymarch is the shared body on the pool.
#include <algorithm>
#include <vector>

#include "engine/cpu/cpu_backend.h"
#include "engine/cpu/cpu_raymarch_lanes.h"
#include "engine/kernels/atom_body.h"
#include "engine/kernels/atom_checks.h"
#include "engine/kernels/grid_cell.h"
#include "engine/kernels/volume_math.h"

namespace masav::cpu {

void CpuBackend::run_own(const KernelArgs<KernelId::voxelize>& a) {
  auto& [p, items_, positions, light, probability, mean_light, sample] = a;
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
    const grid::CellCoord c =
        grid::point_cell(float(pos[4 * i]), float(pos[4 * i + 1]), float(pos[4 * i + 2]), origin,
                         p.grid.inv_cell, dims);
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

void CpuBackend::raymarch_fp32(const RaymarchParams& p, const Buffer<Real>& volume,
                               const Buffer<Real4>& tf, const Buffer<Real4>& bricks,
                               Buffer<Real4>& image, const Buffer<Real4>* tf_integral) {
  const char* k = "raymarch";
  const RaymarchLayout c = raymarch_layout(p);
  const size_t voxels = size_t(c.dims.x) * c.dims.y * c.dims.z;
  const UVec3 nb = brick_dims(p.volume, p.brick);
  const size_t brick_count = size_t(nb.x) * nb.y * nb.z;
  const bool lanes = raymarch_lanes_apply(c);
  // fp32 copies of what the rays read (a fraction of a frame's work: one read per voxel); padded
  // by a voxel on each axis for the lanes.
  std::vector<float> vol;
  std::vector<hd::V4<float>> tf32(p.tf_size), bricks32(brick_count), integral32;
  const double* vd = own(volume.impl(), k).as<double>();
  if (lanes) {
    vol.resize(size_t(c.dims.x + 1) * (c.dims.y + 1) * (c.dims.z + 1));
    pool_.parallel_for(c.dims.z + 1, 1, [&](size_t b, size_t e) {
      pad_volume(vd, c.dims, uint32_t(b), uint32_t(e), vol.data());
    });
  } else {
    vol.resize(voxels);
    pool_.parallel_for(voxels, 1 << 16, [&](size_t b, size_t e) {
      for (size_t i = b; i < e; ++i) vol[i] = float(vd[i]);
    });
  }
  auto to_float4 = [](const double* d, std::vector<hd::V4<float>>& out) {
    for (size_t i = 0; i < out.size(); ++i)
      out[i] = {float(d[4 * i]), float(d[4 * i + 1]), float(d[4 * i + 2]), float(d[4 * i + 3])};
  };
  to_float4(own(tf.impl(), k).as<double>(), tf32);
  to_float4(own(bricks.impl(), k).as<double>(), bricks32);
  if (p.preintegrate) {
    integral32.resize(size_t(kPreintegratedPerEntry) * p.tf_size);
    to_float4(own(tf_integral->impl(), k).as<double>(), integral32);
  }
  double* out = own(image.impl(), k).as<double>();
  // One row of 8x8 tiles per task: neighbouring rays share bricks and cache lines, and rows of
  // uneven cost balance over the pool.
  const uint32_t tile_px = volume::kRayTile * volume::kRayTile;
  const uint32_t tiles_x = (p.width + volume::kRayTile - 1) / volume::kRayTile;
  const uint32_t tile_rows = (p.height + volume::kRayTile - 1) / volume::kRayTile;
  pool_.run_chunks(tile_rows, tile_rows, [&](size_t, size_t b, size_t e) {
    if (lanes) {
      raymarch_lanes(c, vol.data(), tf32.data(), bricks32.data(), integral32.data(),
                     b * tiles_x * tile_px, e * tiles_x * tile_px, out);
      return;
    }
    for (size_t id = b * tiles_x * tile_px; id < e * tiles_x * tile_px; ++id) {
      uint32_t x, y;
      if (!volume::tile_pixel(c, uint32_t(id), x, y)) continue;
      const volume::V4<float> o = KernelBody<KernelId::raymarch>::pixel<float>(
          c, x, y, vol.data(), tf32.data(), bricks32.data(), integral32.data());
      double* px = out + 4 * (size_t(y) * p.width + x);
      px[0] = o.r;
      px[1] = o.g;
      px[2] = o.b;
      px[3] = o.a;
    }
  });
}

}  // namespace masav::cpu

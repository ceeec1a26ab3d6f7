// Voxelization, brick ranges and ray casting on the CPU reference (double precision).
#include <algorithm>
#include <vector>

#include "engine/cpu/cpu_backend.h"
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

}  // namespace masav::cpu

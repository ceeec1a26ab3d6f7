// SphRanks: the decomposition (the partition of the cells, its balance), the initial scatter,
// and the reductions and gathers over the ranks. The particle moves of a rebuild and the halo
// updates are in sph_rank_exchange.cpp.
#include "engine/sph/sph_ranks.h"

#include <algorithm>
#include <cstring>
#include <span>

#include "engine/kernels/grid_cell.h"
#include "engine/kernels/sph_kernel_params.h"

namespace masav {

SphRanks::SphRanks(SphComm& comm, Backend& backend, const GridParams& grid)
    : comm_(comm), backend_(backend), grid_(grid) {
  cell_count_ = uint32_t(grid_cell_count(grid_));
  partition_ = balance_partition({}, 1, cell_count_, comm_.size());
  halo_send_.assign(size_t(comm_.size()), {});
  halo_recv_.assign(size_t(comm_.size()), 0);
}

uint32_t SphRanks::cell_of(const std::byte* real4) const {
  float p[3];
  if (backend_.real_bytes() == 8) {
    double d[3];
    std::memcpy(d, real4, sizeof d);
    for (int a = 0; a < 3; ++a) p[a] = float(d[a]);
  } else {
    std::memcpy(p, real4, sizeof p);
  }
  // As the grid kernels compute it (engine/kernels/grid_body.h): fp32, clamped to the grid.
  const float origin[3] = {grid_.origin.x, grid_.origin.y, grid_.origin.z};
  const uint32_t dims[3] = {grid_.dims.x, grid_.dims.y, grid_.dims.z};
  const grid::CellCoord c = grid::point_cell(p[0], p[1], p[2], origin, grid_.inv_cell, dims);
  return grid::cell_id(c.x, c.y, c.z, dims[1], dims[2]);
}

SphPartition SphRanks::partition_for(const std::vector<uint32_t>& cells, bool global) {
  const uint32_t per = partition_bucket_cells(cell_count_);
  std::vector<uint64_t> counts((uint64_t(cell_count_) + per - 1) / per, 0);
  for (uint32_t c : cells) ++counts[c / per];
  if (global) comm_.sum(counts);
  SphPartition p = balance_partition(counts, per, cell_count_, comm_.size());
  // The imbalance this partition reaches: no partition on these buckets does better.
  std::vector<uint64_t> held(size_t(comm_.size()), 0);
  uint64_t total = 0;
  for (size_t b = 0; b < counts.size(); ++b) {
    held[size_t(p.owner(uint32_t(std::min<uint64_t>(uint64_t(b) * per, cell_count_ - 1))))] +=
        counts[b];
    total += counts[b];
  }
  const double mean = double(total) / double(comm_.size());
  reachable_ = total ? double(*std::max_element(held.begin(), held.end())) / mean - 1.0 : 0.0;
  return p;
}

void SphRanks::maybe_rebalance(const std::vector<uint32_t>& cells) {
  uint32_t most = uint32_t(cells.size());
  uint64_t total = cells.size();
  comm_.max(std::span<uint32_t>(&most, 1));
  comm_.sum(std::span<uint64_t>(&total, 1));
  const double mean = double(total) / double(comm_.size());
  // Beyond the threshold, and by as much beyond what the last balance could reach (few
  // particles in few cells cannot be balanced finer than a bucket: no balance every step).
  if (double(most) <= (1.0 + std::max(kImbalance, reachable_ + kImbalance)) * mean) return;
  partition_ = partition_for(cells, true);
  ++counters_.rebalances;
}

std::vector<uint32_t> SphRanks::cells_of(const std::vector<Vec4d>& positions) const {
  std::vector<uint32_t> cells(positions.size());
  for (size_t i = 0; i < positions.size(); ++i) {
    // The cell of the position as the backend will store it.
    const Vec4d& p = positions[i];
    std::byte raw[32];
    if (backend_.real_bytes() == 8) {
      const double d[4] = {p.x, p.y, p.z, p.w};
      std::memcpy(raw, d, sizeof d);
    } else {
      const float f[4] = {float(p.x), float(p.y), float(p.z), float(p.w)};
      std::memcpy(raw, f, sizeof f);
    }
    cells[i] = cell_of(raw);
  }
  return cells;
}

void SphRanks::balance(const std::vector<Vec4d>& positions) {
  partition_ = partition_for(cells_of(positions), false);  // every rank has every particle
}

std::pair<size_t, size_t> SphRanks::share(size_t count) const {
  const size_t r = size_t(rank()), n = size_t(ranks());
  return {count * r / n, count * (r + 1) / n};
}

void SphRanks::scatter_by_id(const std::vector<Vec4d>& positions,
                             const std::vector<Vec4d>& velocities, bool balance, Buffer<Real4>& x,
                             Buffer<Real4>& v, Buffer<uint32_t>& ids) {
  const std::vector<uint32_t> cells = cells_of(positions);
  if (balance) partition_ = partition_for(cells, false);  // every rank has every particle
  std::vector<Vec4d> own_x, own_v;
  std::vector<uint32_t> own_ids;
  for (size_t i = 0; i < positions.size(); ++i) {
    if (partition_.owner(cells[i]) != rank()) continue;
    own_x.push_back(positions[i]);
    own_v.push_back(velocities[i]);
    own_ids.push_back(uint32_t(i));
  }
  if (reserve_) reserve_(uint32_t(own_x.size()));
  backend_.upload(x, own_x);
  backend_.upload(v, own_v);
  backend_.upload(ids, own_ids);
  const uint32_t own = uint32_t(own_ids.size());
  restore({own, 0, own});
}

void SphRanks::restore(const SphRankLayout& committed) {
  committed_ = staged_ = committed;
  halo_send_.assign(size_t(ranks()), {});
  halo_recv_.assign(size_t(ranks()), 0);
  lo_end_ = 0;
  hi_begin_ = committed.own;
}

std::vector<Bytes> SphRanks::transfer(const std::vector<Bytes>& out) {
  Timer in_mpi(counters_.mpi_seconds);
  return comm_.exchange(out);
}

void SphRanks::reduce_stats(uint32_t* words) {
  Timer timer(counters_.reduce_seconds);
  uint64_t outside = words[kSphStatOutside];
  comm_.max(std::span<uint32_t>(words, kSphStatWords));
  comm_.sum(std::span<uint64_t>(&outside, 1));
  words[kSphStatOutside] = uint32_t(std::min<uint64_t>(outside, UINT32_MAX));
}

uint32_t SphRanks::min(uint32_t value) {
  uint32_t inverted = ~value;
  comm_.max(std::span<uint32_t>(&inverted, 1));
  return ~inverted;
}

uint64_t SphRanks::sum(uint64_t value) {
  Timer timer(counters_.reduce_seconds);
  comm_.sum(std::span<uint64_t>(&value, 1));
  return value;
}

Bytes SphRanks::gather(const Bytes& mine) {
  const std::vector<Bytes> all = comm_.allgather(mine);
  Bytes out;
  for (const Bytes& b : all) out.insert(out.end(), b.begin(), b.end());
  return out;
}

}  // namespace masav

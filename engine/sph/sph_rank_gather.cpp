// The own particles' reads on several ranks (own_values), their gathers (gather_own) and the
// whole state's gather for download().
#include "engine/sph/sph_rank_gather.h"

#include <fmt/format.h>

#include <algorithm>
#include <cstring>
#include <span>

#include "engine/core/error.h"

namespace masav {
namespace {

// One particle of the gathered state.
struct GatheredParticle {
  uint32_t id;
  double position[4], velocity[4], density, pressure, neighbors;
};

// Reals of the backend's precision, `scalars` of them, from the device bytes at `offset`.
std::vector<double> read_reals(Backend& backend, const BufferImpl& b, size_t offset,
                               size_t scalars) {
  std::vector<double> out(scalars);
  if (backend.real_bytes() == 8) {
    backend.download_bytes(b, out.data(), scalars * 8, offset * 8);
  } else {
    std::vector<float> narrow(scalars);
    backend.download_bytes(b, narrow.data(), scalars * 4, offset * 4);
    std::copy(narrow.begin(), narrow.end(), out.begin());
  }
  return out;
}

template <class T, class Elem>
std::vector<T> gather_own_values(Backend& backend, SphRanks& ranks, const Buffer<Elem>& b) {
  const std::vector<T> mine_values = own_values(backend, ranks, b);
  Bytes mine;
  append_bytes(mine, std::span<const T>(mine_values));
  const Bytes bytes = ranks.gather(mine);
  std::vector<T> out(bytes.size() / sizeof(T));
  std::memcpy(out.data(), bytes.data(), out.size() * sizeof(T));
  return out;
}

}  // namespace

std::vector<Vec4d> own_values(Backend& backend, const SphRanks& ranks, const Buffer<Real4>& b) {
  const SphRankLayout& l = ranks.committed();
  const std::vector<double> flat = read_reals(backend, b.impl(), 4 * size_t(l.first), 4 * l.own);
  std::vector<Vec4d> out(l.own);
  for (size_t i = 0; i < l.own; ++i)
    out[i] = {flat[4 * i], flat[4 * i + 1], flat[4 * i + 2], flat[4 * i + 3]};
  return out;
}
std::vector<double> own_values(Backend& backend, const SphRanks& ranks, const Buffer<Real>& b) {
  const SphRankLayout& l = ranks.committed();
  return read_reals(backend, b.impl(), l.first, l.own);
}
std::vector<uint32_t> own_values(Backend& backend, const SphRanks& ranks,
                                 const Buffer<uint32_t>& b) {
  const SphRankLayout& l = ranks.committed();
  std::vector<uint32_t> out(l.own);
  backend.download_bytes(b.impl(), out.data(), size_t(l.own) * 4, size_t(l.first) * 4);
  return out;
}

std::vector<Vec4d> gather_own(Backend& backend, SphRanks& ranks, const Buffer<Real4>& b) {
  return gather_own_values<Vec4d>(backend, ranks, b);
}
std::vector<double> gather_own(Backend& backend, SphRanks& ranks, const Buffer<Real>& b) {
  return gather_own_values<double>(backend, ranks, b);
}
std::vector<uint32_t> gather_own(Backend& backend, SphRanks& ranks, const Buffer<uint32_t>& b) {
  return gather_own_values<uint32_t>(backend, ranks, b);
}

SphState gather_state(Backend& backend, SphRanks& ranks, const SphState& own,
                      const std::vector<uint32_t>& ids, uint32_t n) {
  std::vector<GatheredParticle> mine(ids.size());
  for (size_t k = 0; k < ids.size(); ++k) {
    const Vec4d &x = own.positions[k], &v = own.velocities[k];
    mine[k] = {ids[k],         {x.x, x.y, x.z, x.w}, {v.x, v.y, v.z, v.w},
               own.density[k], own.pressure[k],      own.neighbors[k]};
  }
  Bytes bytes;
  append_bytes(bytes, std::span<const GatheredParticle>(mine));
  const Bytes all = ranks.gather(bytes);
  if (all.size() != size_t(n) * sizeof(GatheredParticle))
    throw Error(backend.name(), "sph ranks",
                fmt::format("the ranks hold {} bytes of particles, {} expected for {}", all.size(),
                            size_t(n) * sizeof(GatheredParticle), n),
                "start every rank with the same masav and the same arguments");
  SphState s = sized_state(n);
  std::vector<bool> seen(n, false);
  for (size_t k = 0; k < n; ++k) {
    GatheredParticle g;
    std::memcpy(&g, all.data() + k * sizeof g, sizeof g);
    if (g.id >= n || seen[g.id])
      throw Error(backend.name(), "sph ranks",
                  fmt::format("particle id {} is missing or held by two ranks", g.id),
                  "start every rank with the same masav and the same arguments");
    seen[g.id] = true;
    s.positions[g.id] = {g.position[0], g.position[1], g.position[2], g.position[3]};
    s.velocities[g.id] = {g.velocity[0], g.velocity[1], g.velocity[2], g.velocity[3]};
    s.density[g.id] = g.density;
    s.pressure[g.id] = g.pressure;
    s.neighbors[g.id] = g.neighbors;
  }
  return s;
}

}  // namespace masav

#include "engine/sph/sph_case_buffers.h"

#include <fmt/format.h>

#include <algorithm>

#include "engine/kernels/kernel_checks.h"

namespace masav {

SphCaseBuffers upload_sph_case(Backend& b, const SphStepParams& p, std::span<const Vec4f> positions,
                               std::span<const Vec4f> velocities, std::string_view label) {
  const uint32_t n = p.n;
  auto name = [&](const char* what) { return fmt::format("{} {}", label, what); };
  SphCaseBuffers s;
  s.pos = b.create<Real4>(n, name("positions"));
  s.vel = b.create<Real4>(n, name("velocities"));
  s.sorted_pos = b.create<Real4>(n, name("sorted positions"));
  s.sorted_vel = b.create<Real4>(n, name("sorted velocities"));
  s.accel = b.create<Real4>(n, name("accel"));
  s.density = b.create<Real>(n, name("density"));
  s.pressure = b.create<Real>(n, name("pressure"));
  s.stats = b.create<uint32_t>(kSphStatWords, name("stats"));
  s.neighbor_rows = b.create<uint32_t>(size_t(kSphRowMaskWords) * n, name("neighbour row masks"));
  b.upload(s.pos, positions);
  b.upload(s.vel, velocities);
  s.grid = make_hash_grid(b, p.grid, n);
  // The counting build, which the SPH kernels need (SphGridView::prefix_ranges); a cell may hold
  // as many points as a walk could examine.
  build_hash_grid(b, s.grid, s.pos,
                  {GridBuild::counting, std::max(1u, std::min(n, max_walk_candidates(b)))});
  reorder(b, s.grid, s.pos.impl(), s.sorted_pos.impl());
  reorder(b, s.grid, s.vel.impl(), s.sorted_vel.impl());
  b.fill(s.stats, 0u);
  return s;
}

}  // namespace masav

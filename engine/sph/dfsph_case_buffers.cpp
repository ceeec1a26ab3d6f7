#include "engine/sph/dfsph_case_buffers.h"

#include <fmt/format.h>

namespace masav {

DfsphCaseBuffers make_dfsph_buffers(Backend& b, uint32_t n, std::string_view label) {
  auto name = [&](const char* what) { return fmt::format("{} {}", label, what); };
  DfsphCaseBuffers d;
  d.factor = b.create<Real>(n, name("factor"));
  d.kappa = b.create<Real>(n, name("kappa"));
  d.kappa_sum = b.create<Real>(n, name("kappa sum"));
  d.residual = b.create<uint32_t>(kDfsphResidualWords, name("residual"));
  b.fill(d.kappa_sum, 0u);
  b.fill(d.residual, 0u);
  return d;
}

DfsphIO dfsph_io(SphCaseBuffers& s, DfsphCaseBuffers& d, bool masked) {
  DfsphIO io;
  io.positions = &s.sorted_pos;
  io.velocities = &s.sorted_vel;
  io.density = &s.density;
  io.factor = &d.factor;
  io.grid = s.view();
  io.kappa = &d.kappa;
  io.kappa_sum = &d.kappa_sum;
  io.residual = &d.residual;
  io.stats = &s.stats;
  io.neighbor_rows = masked ? &s.neighbor_rows : nullptr;
  return io;
}

}  // namespace masav

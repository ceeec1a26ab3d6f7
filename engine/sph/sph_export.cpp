#include "engine/sph/sph_export.h"

#include "engine/io/vtk_writer.h"

namespace masav {

void write_sph_vtp(const std::string& path, const SphState& s) {
  const size_t n = s.positions.size();
  std::vector<float> points(3 * n);
  VtkArray vel{"velocity", 3, std::vector<float>(3 * n)};
  VtkArray rho{"density", 1, std::vector<float>(n)};
  VtkArray pr{"pressure", 1, std::vector<float>(n)};
  VtkArray id{"id", 1, std::vector<float>(n)};
  VtkArray inv_mass{"inverse_mass", 1, std::vector<float>(n)};
  for (size_t i = 0; i < n; ++i) {
    points[3 * i] = float(s.positions[i].x);
    points[3 * i + 1] = float(s.positions[i].y);
    points[3 * i + 2] = float(s.positions[i].z);
    vel.values[3 * i] = float(s.velocities[i].x);
    vel.values[3 * i + 1] = float(s.velocities[i].y);
    vel.values[3 * i + 2] = float(s.velocities[i].z);
    rho.values[i] = float(s.density[i]);
    pr.values[i] = float(s.pressure[i]);
    id.values[i] = float(i);
    inv_mass.values[i] = float(s.positions[i].w);
  }
  write_vtp(path, points, {vel, rho, pr, id, inv_mass});
}

}  // namespace masav

#include "engine/sph/sph_export.h"

#include "engine/io/vtk_writer.h"

namespace masav {
namespace {

// The arrays of an SPH .vtp, in this order (and their declarations in the .pvtp).
std::vector<VtkArray> sph_arrays(size_t n) {
  return {{"velocity", 3, std::vector<float>(3 * n)},
          {"density", 1, std::vector<float>(n)},
          {"pressure", 1, std::vector<float>(n)},
          {"id", 1, std::vector<float>(n)},
          {"inverse_mass", 1, std::vector<float>(n)}};
}

template <class IdOf>
void write_particles(const std::string& path, const SphState& s, IdOf id_of) {
  const size_t n = s.positions.size();
  std::vector<float> points(3 * n);
  std::vector<VtkArray> a = sph_arrays(n);
  VtkArray &vel = a[0], &rho = a[1], &pr = a[2], &id = a[3], &inv_mass = a[4];
  for (size_t i = 0; i < n; ++i) {
    points[3 * i] = float(s.positions[i].x);
    points[3 * i + 1] = float(s.positions[i].y);
    points[3 * i + 2] = float(s.positions[i].z);
    vel.values[3 * i] = float(s.velocities[i].x);
    vel.values[3 * i + 1] = float(s.velocities[i].y);
    vel.values[3 * i + 2] = float(s.velocities[i].z);
    rho.values[i] = float(s.density[i]);
    pr.values[i] = float(s.pressure[i]);
    id.values[i] = float(id_of(i));
    inv_mass.values[i] = float(s.positions[i].w);
  }
  write_vtp(path, points, a);
}

}  // namespace

void write_sph_vtp(const std::string& path, const SphState& s) {
  write_particles(path, s, [](size_t i) { return i; });
}

void write_sph_vtp(const std::string& path, const SphState& s, const std::vector<uint32_t>& ids) {
  write_particles(path, s, [&](size_t i) { return ids.at(i); });
}

void write_sph_pvtp(const std::string& path, const std::vector<std::string>& pieces) {
  write_pvtp(path, sph_arrays(0), pieces);
}

}  // namespace masav

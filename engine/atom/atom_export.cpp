#include "engine/atom/atom_export.h"

#include "engine/io/png_writer.h"
#include "engine/io/vtk_writer.h"

namespace masav::atom {

void write_cloud_vtp(AtomScene& scene, const std::string& path) {
  Backend& b = scene.backend();
  const std::vector<Vec4f> pos = b.download_f32(scene.positions);
  std::vector<float> xyz;
  xyz.reserve(pos.size() * 3);
  for (const Vec4f& p : pos) xyz.insert(xyz.end(), {p.x, p.y, p.z});
  std::vector<VtkArray> arrays;
  auto add = [&](const char* name, const Buffer<Real>& buf) {
    if (!buf) return;
    const std::vector<double> v = b.download(buf);
    arrays.push_back({name, 1, std::vector<float>(v.begin(), v.end())});
  };
  add("light", scene.light);
  add("illumination", scene.illumination);
  const OrbitalState& s = scene.options().state;
  VtkArray state{"state", 3, {}};
  state.values.reserve(pos.size() * 3);
  for (size_t i = 0; i < pos.size(); ++i)
    state.values.insert(state.values.end(), {float(s.n), float(s.l), float(s.m)});
  arrays.push_back(std::move(state));
  write_vtp(path, xyz, arrays);
}

void write_scalar_vti(const VolumeDesc& d, const std::vector<double>& values,
                      const std::string& name, const std::string& path) {
  const uint32_t dims[3] = {d.dims.x, d.dims.y, d.dims.z};
  const double spacing[3] = {(double(d.box_max.x) - d.box_min.x) / d.dims.x,
                             (double(d.box_max.y) - d.box_min.y) / d.dims.y,
                             (double(d.box_max.z) - d.box_min.z) / d.dims.z};
  // Points are the voxel centres, half a voxel inside the box.
  const double origin[3] = {d.box_min.x + 0.5 * spacing[0], d.box_min.y + 0.5 * spacing[1],
                            d.box_min.z + 0.5 * spacing[2]};
  write_vti(path, dims, origin, spacing, {{name, 1, std::vector<float>(values.begin(), values.end())}});
}

void write_volume_vti(AtomScene& scene, const std::string& path) {
  Backend& b = scene.backend();
  const VolumeDesc d = scene.volume();
  const uint32_t dims[3] = {d.dims.x, d.dims.y, d.dims.z};
  const double cell = scene.volume_grid().cell_size;
  const double spacing[3] = {cell, cell, cell};
  const double origin[3] = {d.box_min.x + 0.5 * cell, d.box_min.y + 0.5 * cell,
                            d.box_min.z + 0.5 * cell};
  std::vector<VtkArray> arrays;
  auto add = [&](const char* name, const Buffer<Real>& buf) {  // already x fastest
    const std::vector<double> v = b.download(buf);
    arrays.push_back({name, 1, std::vector<float>(v.begin(), v.end())});
  };
  add("p", scene.probability);
  add("g", scene.mean_light);
  add("sample", scene.sample);
  write_vti(path, dims, origin, spacing, arrays);
}

void write_image_png(const std::vector<Vec4d>& image, uint32_t width, uint32_t height,
                     const std::string& path) {
  write_png(path, width, height, to_rgba8(image));
}

}  // namespace masav::atom

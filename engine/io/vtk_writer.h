#pragma once
// VTK XML files for ParaView: particles as PolyData (.vtp), volumes as ImageData (.vti). Arrays
// are stored inline as base64 binary (format="binary"), little-endian; files are written to a
// temporary name and renamed.
#include <cstdint>
#include <string>
#include <vector>

namespace masav {

struct VtkArray {
  std::string name;
  int components = 1;         // 1 scalar, 3 vector
  std::vector<float> values;  // count * components, point-major
};

// points: x, y, z per point (3 * count floats).
void write_vtp(const std::string& path, const std::vector<float>& points,
               const std::vector<VtkArray>& point_data);

// The index of a particle set written in pieces (one .vtp per rank): ParaView's parallel
// PolyData (.pvtp) naming each piece's file (relative to the .pvtp's directory) and declaring
// the arrays every piece holds (`point_data`: names and components; values unused).
void write_pvtp(const std::string& path, const std::vector<VtkArray>& point_data,
                const std::vector<std::string>& pieces);

// A volume of dims.x * dims.y * dims.z points, x fastest; origin and spacing in world units.
void write_vti(const std::string& path, const uint32_t dims[3], const double origin[3],
               const double spacing[3], const std::vector<VtkArray>& point_data);

std::string base64(const void* data, size_t bytes);

}  // namespace masav

#include "engine/io/vtk_writer.h"

#include <fmt/format.h>

#include <cstring>

#include "engine/core/error.h"
#include "engine/util/json_writer.h"

namespace masav {
namespace {

// VTK's inline binary: base64 of (UInt32 byte count, then the raw bytes).
std::string encode_array(const std::vector<float>& v) {
  const uint32_t bytes = uint32_t(v.size() * sizeof(float));
  std::string raw(sizeof bytes + bytes, '\0');
  std::memcpy(raw.data(), &bytes, sizeof bytes);
  if (bytes) std::memcpy(raw.data() + sizeof bytes, v.data(), bytes);
  return base64(raw.data(), raw.size());
}

std::string data_array(const VtkArray& a) {
  return fmt::format(
      "        <DataArray type=\"Float32\" Name=\"{}\" NumberOfComponents=\"{}\" "
      "format=\"binary\">\n{}\n        </DataArray>\n",
      a.name, a.components, encode_array(a.values));
}

void check_arrays(const std::vector<VtkArray>& arrays, size_t count, const std::string& path) {
  for (const auto& a : arrays)
    if (a.components < 1 || a.values.size() != count * size_t(a.components))
      throw Error("", "vtk export",
                  fmt::format("array '{}' has {} values for {} points x {} components ({})", a.name,
                              a.values.size(), count, a.components, path),
                  "internal error: report it");
  if (count * 16 > UINT32_MAX)
    throw Error("", "vtk export", fmt::format("{} points exceed one VTK binary block", count),
                "export fewer points");
}

}  // namespace

std::string base64(const void* data, size_t bytes) {
  static const char* t = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  const auto* p = static_cast<const unsigned char*>(data);
  std::string out;
  out.reserve((bytes + 2) / 3 * 4);
  for (size_t i = 0; i < bytes; i += 3) {
    const uint32_t b0 = p[i], b1 = i + 1 < bytes ? p[i + 1] : 0, b2 = i + 2 < bytes ? p[i + 2] : 0;
    const uint32_t v = b0 << 16 | b1 << 8 | b2;
    out += t[v >> 18 & 63];
    out += t[v >> 12 & 63];
    out += i + 1 < bytes ? t[v >> 6 & 63] : '=';
    out += i + 2 < bytes ? t[v & 63] : '=';
  }
  return out;
}

void write_vtp(const std::string& path, const std::vector<float>& points,
               const std::vector<VtkArray>& point_data) {
  if (points.size() % 3)
    throw Error("", "vtk export", "point coordinates are not triples", "internal error");
  const size_t n = points.size() / 3;
  check_arrays(point_data, n, path);
  std::string body = fmt::format(
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"LittleEndian\" "
      "header_type=\"UInt32\">\n  <PolyData>\n"
      "    <Piece NumberOfPoints=\"{}\" NumberOfVerts=\"0\" NumberOfLines=\"0\" "
      "NumberOfStrips=\"0\" NumberOfPolys=\"0\">\n      <PointData>\n",
      n);
  for (const auto& a : point_data) body += data_array(a);
  body += "      </PointData>\n      <Points>\n";
  body += data_array(VtkArray{"Points", 3, points});
  body += "      </Points>\n    </Piece>\n  </PolyData>\n</VTKFile>\n";
  write_file_atomic(path, body);
}

void write_pvtp(const std::string& path, const std::vector<VtkArray>& point_data,
                const std::vector<std::string>& pieces) {
  std::string body =
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"PPolyData\" version=\"1.0\" byte_order=\"LittleEndian\" "
      "header_type=\"UInt32\">\n  <PPolyData GhostLevel=\"0\">\n    <PPointData>\n";
  for (const auto& a : point_data)
    body +=
        fmt::format("      <PDataArray type=\"Float32\" Name=\"{}\" NumberOfComponents=\"{}\"/>\n",
                    a.name, a.components);
  body +=
      "    </PPointData>\n    <PPoints>\n"
      "      <PDataArray type=\"Float32\" Name=\"Points\" NumberOfComponents=\"3\"/>\n"
      "    </PPoints>\n";
  for (const auto& piece : pieces) body += fmt::format("    <Piece Source=\"{}\"/>\n", piece);
  body += "  </PPolyData>\n</VTKFile>\n";
  write_file_atomic(path, body);
}

void write_vti(const std::string& path, const uint32_t dims[3], const double origin[3],
               const double spacing[3], const std::vector<VtkArray>& point_data) {
  const size_t n = size_t(dims[0]) * dims[1] * dims[2];
  check_arrays(point_data, n, path);
  std::string body = fmt::format(
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"ImageData\" version=\"1.0\" byte_order=\"LittleEndian\" "
      "header_type=\"UInt32\">\n"
      "  <ImageData WholeExtent=\"0 {} 0 {} 0 {}\" Origin=\"{} {} {}\" Spacing=\"{} {} {}\">\n"
      "    <Piece Extent=\"0 {} 0 {} 0 {}\">\n      <PointData>\n",
      dims[0] - 1, dims[1] - 1, dims[2] - 1, origin[0], origin[1], origin[2], spacing[0],
      spacing[1], spacing[2], dims[0] - 1, dims[1] - 1, dims[2] - 1);
  for (const auto& a : point_data) body += data_array(a);
  body += "      </PointData>\n    </Piece>\n  </ImageData>\n</VTKFile>\n";
  write_file_atomic(path, body);
}

}  // namespace masav

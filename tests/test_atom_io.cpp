// Files of the electron-cloud scene (no backend): volume loaders (raw, NRRD, VTI) and their
// errors, the .vti export read back, transfer-function files, the scattering-table cache key.
#include <doctest/doctest.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "engine/atom/atom_export.h"
#include "engine/atom/scatter_cache.h"
#include "engine/core/error.h"
#include "engine/volume/transfer_function.h"
#include "engine/volume/volume_io.h"
#include "tests/temp_dir.h"

using namespace masav;
using namespace masav::atom;
using namespace masav::volume;

namespace {

void write_bytes(const std::string& path, const void* data, size_t n,
                 const std::string& head = "") {
  std::ofstream out(path, std::ios::binary);
  out << head;
  out.write(static_cast<const char*>(data), std::streamsize(n));
}

std::vector<uint16_t> ramp16(UVec3 d) {
  std::vector<uint16_t> v;
  for (uint32_t k = 0; k < d.z; ++k)
    for (uint32_t j = 0; j < d.y; ++j)
      for (uint32_t i = 0; i < d.x; ++i) v.push_back(uint16_t(i + 10 * j + 100 * k));
  return v;
}

}  // namespace

TEST_CASE("raw volumes: dims and type given; a size that does not match the dims is an error") {
  test::TempDir t("masav_atom_io");
  const UVec3 d{4, 3, 2};
  const auto v = ramp16(d);
  write_bytes(t.file("a.raw"), v.data(), v.size() * 2);
  const ScalarVolume vol = load_raw(t.file("a.raw"), d, parse_sample_type("uint16"));
  CHECK(vol.values.size() == 24);
  CHECK(vol.values[1 + 4 * 2 + 12 * 1] == 121.0f);  // x fastest
  CHECK(vol.min == 0.0f);
  CHECK(vol.max == 123.0f);
  CHECK_THROWS_WITH_AS(load_raw(t.file("a.raw"), {4, 3, 3}, SampleType::u16),
                       doctest::Contains("invalid dims = 4x3x3"), Error);
  CHECK_THROWS_WITH_AS(load_raw(t.file("a.raw"), d, SampleType::f32),
                       doctest::Contains("the dims need 24"), Error);
  CHECK_THROWS_WITH_AS(parse_sample_type("uint12"), doctest::Contains("invalid type = uint12"),
                       Error);
  CHECK_THROWS_WITH_AS(load_raw(t.file("missing.raw"), d, SampleType::u8),
                       doctest::Contains("missing.raw' does not exist"), Error);
  // Big-endian samples.
  std::vector<uint16_t> be(v);
  for (auto& x : be) x = uint16_t(x << 8 | x >> 8);
  write_bytes(t.file("b.raw"), be.data(), be.size() * 2);
  CHECK(load_raw(t.file("b.raw"), d, SampleType::u16, true).values == vol.values);
  const VolumeDesc desc = volume_desc(vol);
  CHECK(desc.box_max.x == 4.0f);
  CHECK(desc.value_max == 123.0f);
}

TEST_CASE("NRRD volumes: attached and detached data, raw and ASCII; bad headers named") {
  test::TempDir t("masav_atom_io");
  const UVec3 d{4, 3, 2};
  const auto v = ramp16(d);
  const std::string head =
      "NRRD0004\n# a comment\ntype: unsigned short\ndimension: 3\nsizes: 4 3 2\n"
      "spacings: 0.5 0.5 2\nencoding: raw\nendian: little\n\n";
  write_bytes(t.file("a.nrrd"), v.data(), v.size() * 2, head);
  const ScalarVolume a = load_nrrd(t.file("a.nrrd"));
  CHECK(a.values.size() == 24);
  CHECK(a.values[23] == 123.0f);
  CHECK(a.spacing.z == 2.0f);
  write_bytes(t.file("b.raw"), v.data(), v.size() * 2);
  const std::string detached =
      "NRRD0004\ntype: uint16\ndimension: 3\nsizes: 4 3 2\nencoding: raw\nendian: little\n"
      "data file: b.raw\n";
  write_bytes(t.file("b.nhdr"), "", 0, detached);
  CHECK(load_nrrd(t.file("b.nhdr")).values == a.values);
  std::string ascii = "NRRD0004\ntype: float\ndimension: 3\nsizes: 2 2 2\nencoding: ascii\n\n";
  ascii += "1 2 3 4 5 6 7 8\n";
  write_bytes(t.file("c.nrrd"), "", 0, ascii);
  CHECK(load_nrrd(t.file("c.nrrd")).values[7] == 8.0f);
  const std::string gz = "NRRD0004\ntype: float\ndimension: 3\nsizes: 2 2 2\nencoding: gzip\n\n";
  write_bytes(t.file("d.nrrd"), "xxxx", 4, gz);
  CHECK_THROWS_WITH_AS(load_nrrd(t.file("d.nrrd")), doctest::Contains("invalid encoding = gzip"),
                       Error);
  write_bytes(t.file("e.nrrd"), v.data(), 40, head);  // short
  CHECK_THROWS_WITH_AS(load_nrrd(t.file("e.nrrd")), doctest::Contains("invalid sizes"), Error);
}

TEST_CASE("VTI volumes: the .vti export reads back; a short array is an error") {
  test::TempDir t("masav_atom_io");
  const VolumeDesc d = make_volume_desc({5, 4, 3}, {-1, -2, -3}, {1, 2, 3});
  std::vector<double> values(60);
  for (size_t i = 0; i < values.size(); ++i) values[i] = 0.25 * double(i);
  write_scalar_vti(d, values, "density", t.file("a.vti"));
  const ScalarVolume v = load_vti(t.file("a.vti"), "density");
  CHECK(v.dims.x == 5);
  CHECK(v.dims.z == 3);
  CHECK(v.values[59] == 14.75f);
  const VolumeDesc back = volume_desc(v);
  CHECK(back.box_min.x == doctest::Approx(-1.0));
  CHECK(back.box_max.z == doctest::Approx(3.0));
  CHECK_THROWS_WITH_AS(load_vti(t.file("a.vti"), "nope"), doctest::Contains("invalid array = nope"),
                       Error);
  const std::string ascii =
      "<?xml version=\"1.0\"?>\n<VTKFile type=\"ImageData\" version=\"1.0\">\n"
      "<ImageData WholeExtent=\"0 1 0 1 0 2\" Origin=\"0 0 0\" Spacing=\"1 1 1\">\n"
      "<Piece Extent=\"0 1 0 1 0 2\"><PointData>\n"
      "<DataArray type=\"Float32\" Name=\"v\" format=\"ascii\">1 2 3 4 5 6 7 8 9 10</DataArray>\n"
      "</PointData></Piece></ImageData></VTKFile>\n";
  write_bytes(t.file("b.vti"), "", 0, ascii);
  CHECK_THROWS_WITH_AS(load_vti(t.file("b.vti")), doctest::Contains("the extent needs 12"), Error);
}

TEST_CASE("transfer functions: default blue -> green -> red, files, and errors naming the line") {
  const auto tf = resample_transfer(default_transfer_points(), 256);
  REQUIRE(tf.size() == 256);
  CHECK(tf[0].z == 1.0);    // blue at the bottom
  CHECK(tf[255].x == 1.0);  // red at the top
  CHECK(tf[255].y == 0.0);
  CHECK(tf[0].w == 0.0);
  const auto pts =
      parse_transfer_points("# comment\n0 0 0 0 0\n0.5 1 0 0 0.5 # mid\n1 1 1 1 1\n", "x");
  CHECK(pts.size() == 3);
  const auto r = resample_transfer(pts, 5);
  CHECK(r[1].x == doctest::Approx(0.5));
  CHECK(r[1].w == doctest::Approx(0.25));
  CHECK_THROWS_WITH_AS(parse_transfer_points("# nothing\n\n", "tf.txt"),
                       doctest::Contains("no entries"), Error);
  CHECK_THROWS_WITH_AS(parse_transfer_points("0 0 0 0\n", "tf.txt"), doctest::Contains("line 1"),
                       Error);
  CHECK_THROWS_WITH_AS(parse_transfer_points("0 0 0 0 2\n", "tf.txt"), doctest::Contains("field a"),
                       Error);
  CHECK_THROWS_WITH_AS(parse_transfer_points("0.5 0 0 0 0\n0.2 0 0 0 0\n", "tf.txt"),
                       doctest::Contains("line 2 field value"), Error);
  CHECK_THROWS_WITH_AS(load_transfer_points("/nonexistent/tf.txt"),
                       doctest::Contains("'/nonexistent/tf.txt' does not exist"), Error);
}

TEST_CASE("the scattering-table cache key names every parameter") {
  ScatterTableParams p;
  const std::string key = scatter_cache_key(p);
  for (const char* field :
       {"rows=", "first_row=", "bins=", "tau_step=", "g=", "albedo=", "threshold=",
        "photons_per_row=", "max_scatterings=", "start=", "direction=", "seed="})
    CHECK(key.find(field) != std::string::npos);
  ScatterTableParams q = p;
  q.weight_threshold = std::nextafter(q.weight_threshold, 1.0f);  // one ulp apart
  CHECK(scatter_cache_key(q) != key);
  CHECK(scatter_cache_path(q, "d") != scatter_cache_path(p, "d"));
}

// Volumes at the edges of their types (issue 45, class 10): every element type written as NRRD
// (little- and big-endian), raw and ASCII at its extremes -- min and max, +-FLT_MAX, beyond
// FLT_MAX in float64, 1e-300, denormals, a range below fp32's resolution, constant volumes --
// reports its range exactly, normalises as the kernels do to the full [0, 1], and raymarches to
// an image that is not black; a multi-byte raw NRRD without `endian` is refused by name.
#include <doctest/doctest.h>

#include <algorithm>
#include <cfloat>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "engine/atom/atom_scene.h"
#include "engine/core/error.h"
#include "engine/volume/transfer_function.h"
#include "engine/volume/volume_io.h"
#include "tests/backend_fixture.h"
#include "tests/temp_dir.h"

using namespace masav;
using namespace masav::volume;

namespace {

constexpr UVec3 kDims{4, 2, 2};  // 16 voxels: the first 8 (the z = 0 slab) low, the rest high
constexpr size_t kCount = 16;

template <class T>
std::string bytes_of(const std::vector<T>& v, bool big) {
  std::string out;
  for (const T x : v) {
    char b[sizeof(T)];
    std::memcpy(b, &x, sizeof(T));
    if (big) std::reverse(b, b + sizeof(T));
    out.append(b, sizeof(T));
  }
  return out;
}

void write_file(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

std::string nrrd_head(const std::string& type, const std::string& endian,
                      const std::string& encoding = "raw") {
  std::string h =
      "NRRD0004\ntype: " + type + "\ndimension: 3\nsizes: 4 2 2\nencoding: " + encoding + "\n";
  if (!endian.empty()) h += "endian: " + endian + "\n";
  return h + "\n";
}

// What the kernels compute for a stored value: (v - value_min) * (1 / width), in fp32.
float normalised(const VolumeDesc& d, float v) {
  return (v - d.value_min) * (1.0f / (d.value_max - d.value_min));
}

double largest_alpha(const ScalarVolume& v) {
  Backend& b = test::backend();
  const VolumeDesc d = volume_desc(v);
  auto buf = b.create<Real>(v.values.size(), "volume");
  b.upload(buf, std::span<const float>(v.values));
  const RaymarchParams rp = atom::default_raymarch(d, atom::ViewPreset::front, 8, 8);
  const auto img = atom::render_volume(b, d, buf, resample_transfer(default_transfer_points()), rp);
  double a = 0;
  for (const Vec4d& p : img) a = std::max(a, p.w);
  return a;
}

template <class T>
std::vector<T> low_high(T lo, T hi) {
  std::vector<T> v(kCount, lo);
  std::fill(v.begin() + kCount / 2, v.end(), hi);
  return v;
}

// Writes lo/hi as `type` in both byte orders (and raw, big-endian), checks each reads back the
// same range [lo, hi] in double and normalises lo to 0 and hi to 1; returns the NRRD's volume.
template <class T>
ScalarVolume check_extremes(const test::TempDir& t, const std::string& type, T lo, T hi) {
  static int serial = 0;
  const std::vector<T> v = low_high(lo, hi);
  const std::string name = t.file(type + std::to_string(++serial));
  write_file(name + "_le.nrrd", nrrd_head(type, "little") + bytes_of(v, false));
  write_file(name + "_be.nrrd", nrrd_head(type, "big") + bytes_of(v, true));
  write_file(name + "_be.raw", bytes_of(v, true));
  const ScalarVolume le = load_nrrd(name + "_le.nrrd");
  const ScalarVolume be = load_nrrd(name + "_be.nrrd");
  const ScalarVolume raw = load_raw(name + "_be.raw", kDims, parse_sample_type(type), true);
  CHECK(le.min == double(lo));
  CHECK(le.max == double(hi));
  CHECK(be.values == le.values);
  CHECK(raw.values == le.values);
  CHECK(be.min == le.min);
  CHECK(be.max == le.max);
  const VolumeDesc d = volume_desc(le);
  CHECK(normalised(d, le.values.front()) == doctest::Approx(0.0).epsilon(1e-6));
  CHECK(normalised(d, le.values.back()) == doctest::Approx(1.0).epsilon(1e-6));
  return le;
}

}  // namespace

TEST_CASE("volume type edges: every type's extremes keep their range and render") {
  test::TempDir t("masav_type_edges");
  std::vector<ScalarVolume> vols;
  SUBCASE("integers") {
    vols.push_back(check_extremes<int8_t>(t, "int8", INT8_MIN, INT8_MAX));
    vols.push_back(check_extremes<uint8_t>(t, "uint8", 0, UINT8_MAX));
    vols.push_back(check_extremes<int16_t>(t, "int16", INT16_MIN, INT16_MAX));
    vols.push_back(check_extremes<uint16_t>(t, "uint16", 0, UINT16_MAX));
    vols.push_back(check_extremes<int32_t>(t, "int32", INT32_MIN, INT32_MAX));
    vols.push_back(check_extremes<uint32_t>(t, "uint32", 0, UINT32_MAX));
    // 100 steps at 2^31, where fp32 has 128 between neighbours: below fp32's resolution.
    vols.push_back(check_extremes<int32_t>(t, "int32", INT32_MAX - 100, INT32_MAX));
  }
  SUBCASE("float32") {
    vols.push_back(check_extremes<float>(t, "float", -FLT_MAX, FLT_MAX));
    vols.push_back(check_extremes<float>(t, "float", 0, FLT_MAX));
    vols.push_back(check_extremes<float>(t, "float", FLT_TRUE_MIN, 3 * FLT_TRUE_MIN));
    vols.push_back(check_extremes<float>(t, "float", -FLT_MIN, FLT_MIN));
  }
  SUBCASE("float64") {
    vols.push_back(check_extremes<double>(t, "double", 1e-300, 2e-300));
    vols.push_back(check_extremes<double>(t, "double", 0, DBL_TRUE_MIN));
    vols.push_back(check_extremes<double>(t, "double", -1e300, 1e300));
    vols.push_back(check_extremes<double>(t, "double", -DBL_MAX, DBL_MAX));
    vols.push_back(check_extremes<double>(t, "double", 1e9, 1e9 + 100));
  }
  for (const ScalarVolume& v : vols) {
    CAPTURE(v.min);
    CAPTURE(v.max);
    CHECK(largest_alpha(v) > 0.01);
  }
}

TEST_CASE("volume type edges: ASCII NRRD keeps a float64 range fp32 cannot hold") {
  test::TempDir t("masav_type_edges");
  std::string text = nrrd_head("double", "", "ascii");
  for (size_t i = 0; i < kCount; ++i) text += i < kCount / 2 ? "1e-300 " : "3e-300 ";
  write_file(t.file("tiny.nrrd"), text);
  const ScalarVolume v = load_nrrd(t.file("tiny.nrrd"));
  CHECK(v.min == 1e-300);
  CHECK(v.max == 3e-300);
  CHECK(normalised(volume_desc(v), v.values.back()) == doctest::Approx(1.0));
  CHECK(largest_alpha(v) > 0.01);
}

TEST_CASE("volume type edges: a constant volume shows at the transfer function's top") {
  test::TempDir t("masav_type_edges");
  const auto constant = [&](const std::string& type, auto c) {
    const std::string file = t.file("constant_" + type + ".nrrd");
    write_file(file, nrrd_head(type, "little") + bytes_of(low_high(c, c), false));
    return load_nrrd(file);
  };
  const ScalarVolume vols[] = {
      constant("uint32", UINT32_MAX), constant("int16", int16_t(INT16_MIN)),
      constant("float", FLT_MAX),     constant("float", -FLT_MAX),
      constant("double", 1e-300),     constant("double", -DBL_MAX),
      constant("uint8", uint8_t(7))};
  for (const ScalarVolume& v : vols) {
    CAPTURE(v.min);
    CHECK(v.min == v.max);
    const VolumeDesc d = volume_desc(v);
    CHECK(normalised(d, v.values[3]) == doctest::Approx(1.0));
    CHECK(largest_alpha(v) > 0.01);
  }
  // Zero is empty space: the bottom of the transfer function, a black image.
  const ScalarVolume zero = constant("uint16", uint16_t(0));
  CHECK(zero.max == 0);
  CHECK(normalised(volume_desc(zero), zero.values[3]) == 0.0f);
  CHECK(largest_alpha(zero) == 0.0);
}

TEST_CASE("volume type edges: a multi-byte raw NRRD must name its endian") {
  test::TempDir t("masav_type_edges");
  const std::string zeros(kCount * 8, '\0');
  const std::pair<const char*, size_t> types[] = {{"uint16", 2}, {"int16", 2}, {"ushort", 2},
                                                  {"uint32", 4}, {"int32", 4}, {"float", 4},
                                                  {"double", 8}};
  for (const auto& [type, bytes] : types) {
    CAPTURE(type);
    write_file(t.file("a.nrrd"), nrrd_head(type, "") + zeros.substr(0, kCount * bytes));
    try {
      load_nrrd(t.file("a.nrrd"));
      FAIL("loaded without an endian field");
    } catch (const Error& e) {
      const std::string what = e.what();
      CHECK(what.find("invalid endian = missing") != std::string::npos);
      CHECK(what.find("little or big") != std::string::npos);
    }
  }
  // One-byte samples have no byte order, and ASCII data none either.
  write_file(t.file("b.nrrd"), nrrd_head("uint8", "") + zeros.substr(0, kCount));
  CHECK(load_nrrd(t.file("b.nrrd")).values.size() == kCount);
  write_file(t.file("c.nrrd"),
             nrrd_head("uint16", "", "ascii") + "1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16\n");
  CHECK(load_nrrd(t.file("c.nrrd")).max == 16);
}

TEST_CASE("volume type edges: non-finite samples are refused, finite float64 beyond fp32 is not") {
  test::TempDir t("masav_type_edges");
  std::vector<float> v(kCount, 1.0f);
  v[5] = std::numeric_limits<float>::quiet_NaN();
  v[9] = std::numeric_limits<float>::infinity();
  write_file(t.file("nan.nrrd"), nrrd_head("float", "little") + bytes_of(v, false));
  CHECK_THROWS_WITH_AS(load_nrrd(t.file("nan.nrrd")),
                       doctest::Contains("2 samples are NaN or infinite"), Error);
  const std::vector<double> big = low_high(1.0, 1e300);
  write_file(t.file("big.nrrd"), nrrd_head("double", "little") + bytes_of(big, false));
  const ScalarVolume b = load_nrrd(t.file("big.nrrd"));
  CHECK(b.max == 1e300);
  CHECK(normalised(volume_desc(b), b.values.back()) == doctest::Approx(1.0));
}

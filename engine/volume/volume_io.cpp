#include "engine/volume/volume_io.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <initializer_list>
#include <map>
#include <optional>
#include <sstream>

#include "engine/core/error.h"
#include "engine/util/bounded_file.h"
#include "engine/util/checked_size.h"
#include "engine/volume/nrrd_header.h"

namespace masav::volume {
namespace {

// Text data (ASCII NRRD or VTI) may spend at most this many bytes per value, and an XML file this
// many on everything else, so a file far larger than its declared size is refused before it is
// read.
constexpr uint64_t kMaxTextBytesPerValue = 64;
constexpr uint64_t kMaxXmlOverheadBytes = kMaxTextInputBytes;

uint64_t voxel_count(UVec3 d) {
  return checked_mul(checked_mul(d.x, d.y, "volume", "dims"), d.z, "volume", "dims");
}

uint64_t data_bytes(UVec3 d, SampleType t) {
  return checked_mul(voxel_count(d), sample_bytes(t), "volume", "dims");
}

void check_dims(UVec3 d, const std::string& where) {
  for (uint32_t v : {d.x, d.y, d.z})
    if (v < 2 || v > 8192)
      throw_invalid(where, "dims", fmt::format("{}x{}x{}", d.x, d.y, d.z), "each in [2, 8192]");
}

template <class T>
double load_one(const unsigned char* p, bool swap) {
  unsigned char b[sizeof(T)];
  std::memcpy(b, p, sizeof(T));
  if (swap) std::reverse(b, b + sizeof(T));
  T v;
  std::memcpy(&v, b, sizeof(T));
  return double(v);
}

// Sample i of `data` in double: every type's values exactly (a float64 beyond fp32's range is
// still finite here).
double raw_sample(const unsigned char* data, size_t i, SampleType t, bool swap) {
  const unsigned char* p = data + i * sample_bytes(t);
  switch (t) {
    case SampleType::u8:
      return load_one<uint8_t>(p, false);
    case SampleType::i8:
      return load_one<int8_t>(p, false);
    case SampleType::u16:
      return load_one<uint16_t>(p, swap);
    case SampleType::i16:
      return load_one<int16_t>(p, swap);
    case SampleType::u32:
      return load_one<uint32_t>(p, swap);
    case SampleType::i32:
      return load_one<int32_t>(p, swap);
    case SampleType::f32:
      return load_one<float>(p, swap);
    case SampleType::f64:
      return load_one<double>(p, swap);
  }
  return 0;
}

// Whether raw samples in [lo, hi] can be fp32 as they are: raymarch normalises in fp32 by
// (v - lo) * (1 / (hi - lo)), which overflows beyond 2^64 (1 / (hi - lo) turns denormal, which
// GPUs flush to 0: a black image), loses the range below 2^-64 (denormal differences), and has
// fewer than 2^12 steps across a range narrower than 2^-12 of the values' magnitude.
bool fits_fp32(double lo, double hi) {
  const double mag = std::max(std::abs(lo), std::abs(hi)), width = hi - lo;
  if (mag > 0x1p64) return false;
  if (width == 0) return lo == 0 || mag >= 0x1p-64;
  return width >= 0x1p-64 && width >= mag * 0x1p-12;
}

// Two passes over `raw(i)`: the range in double, then the fp32 samples (normalised in double
// when fp32 cannot hold the range), so no copy of the volume in double is made.
template <class Raw>
void store(ScalarVolume& v, size_t count, Raw raw, const std::string& where) {
  size_t bad = 0;
  double lo = INFINITY, hi = -INFINITY;
  for (size_t i = 0; i < count; ++i) {
    const double x = raw(i);
    if (!std::isfinite(x)) {
      ++bad;
      continue;
    }
    lo = std::min(lo, x);
    hi = std::max(hi, x);
  }
  if (bad)
    throw Error("", where, fmt::format("{} samples are NaN or infinite", bad),
                "give a volume of finite values");
  v.min = lo;
  v.max = hi;
  v.normalised = !fits_fp32(lo, hi);
  v.values.resize(count);
  if (!v.normalised) {
    for (size_t i = 0; i < count; ++i) v.values[i] = float(raw(i));
    return;
  }
  // Halves keep hi - lo finite near +-DBL_MAX; whole values keep denormal differences exact.
  const bool halve = !std::isfinite(hi - lo);
  const double a = halve ? lo / 2 : lo, width = halve ? hi / 2 - lo / 2 : hi - lo;
  for (size_t i = 0; i < count; ++i) {
    const double x = halve ? raw(i) / 2 : raw(i);
    v.values[i] = width > 0 ? float((x - a) / width) : (x != 0 ? 1.0f : 0.0f);
  }
}

void store_bytes(ScalarVolume& v, const unsigned char* data, size_t count, SampleType t, bool swap,
                 const std::string& where) {
  store(
      v, count, [&](size_t i) { return raw_sample(data, i, t, swap); }, where);
}

void check_spacing(const ScalarVolume& v, const std::string& where) {
  for (float s : {v.spacing.x, v.spacing.y, v.spacing.z})
    if (!std::isfinite(s) || !(s > 0))
      throw_invalid(where, "spacing",
                    fmt::format("({}, {}, {})", v.spacing.x, v.spacing.y, v.spacing.z),
                    "finite and > 0 on every axis");
}

void size_mismatch(const std::string& where, UVec3 d, SampleType t, uint64_t have,
                   const char* field = "dims") {
  throw_invalid(where, field, fmt::format("{}x{}x{}", d.x, d.y, d.z),
                fmt::format("consistent with the data: {} bytes of {}-byte samples hold {} values, "
                            "the dims need {}",
                            have, sample_bytes(t), have / sample_bytes(t), voxel_count(d)));
}

std::vector<uint8_t> base64_decode(std::string_view s, const std::string& where) {
  auto val = [](char c) -> int {
    if (c >= 'A' && c <= 'Z') return c - 'A';
    if (c >= 'a' && c <= 'z') return c - 'a' + 26;
    if (c >= '0' && c <= '9') return c - '0' + 52;
    if (c == '+') return 62;
    if (c == '/') return 63;
    return -1;
  };
  std::vector<uint8_t> out;
  uint32_t acc = 0;
  int bits = 0;
  for (char c : s) {
    if (c == '=' || std::isspace(static_cast<unsigned char>(c))) continue;
    const int v = val(c);
    if (v < 0) throw_invalid(where, "base64 data", std::string(1, c), "base64 characters");
    acc = acc << 6 | uint32_t(v);
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out.push_back(uint8_t(acc >> bits));
    }
  }
  return out;
}

std::map<std::string, std::string> xml_attributes(const std::string& tag) {
  std::map<std::string, std::string> a;
  size_t i = 0;
  while ((i = tag.find('=', i)) != std::string::npos) {
    size_t k = i;
    while (k > 0 && std::isspace(static_cast<unsigned char>(tag[k - 1]))) --k;
    size_t start = k;
    while (start > 0 &&
           (std::isalnum(static_cast<unsigned char>(tag[start - 1])) || tag[start - 1] == '_'))
      --start;
    const size_t q = tag.find('"', i);
    const size_t e = q == std::string::npos ? q : tag.find('"', q + 1);
    if (e == std::string::npos) break;
    a[tag.substr(start, k - start)] = tag.substr(q + 1, e - q - 1);
    i = e + 1;
  }
  return a;
}

SampleType vtk_type(const std::string& t, const std::string& where) {
  static const std::map<std::string, SampleType> m = {
      {"UInt8", SampleType::u8},    {"Int8", SampleType::i8},    {"UInt16", SampleType::u16},
      {"Int16", SampleType::i16},   {"UInt32", SampleType::u32}, {"Int32", SampleType::i32},
      {"Float32", SampleType::f32}, {"Float64", SampleType::f64}};
  const auto it = m.find(t);
  if (it == m.end())
    throw_invalid(where, "DataArray type", t,
                  "one of UInt8, Int8, UInt16, Int16, UInt32, Int32, "
                  "Float32, Float64");
  return it->second;
}

std::vector<double> numbers(const std::string& s) {
  std::vector<double> v;
  std::istringstream in(s);
  double x;
  while (in >> x) v.push_back(x);
  return v;
}

// The offset just after the first `lines` newlines from `from` ("line skip" in NRRD).
uint64_t skip_lines(const BoundedFile& f, uint64_t from, uint64_t lines, const std::string& where) {
  uint64_t at = from;
  for (uint64_t seen = 0; seen < lines;) {
    const std::string chunk = f.read_some(at, 1 << 16);
    if (chunk.empty())
      throw_invalid(where, "line skip", std::to_string(lines),
                    fmt::format("at most the {} lines the data file holds", seen));
    for (size_t i = 0; i < chunk.size() && seen < lines; ++i)
      if (chunk[i] == '\n' && ++seen == lines) return at + i + 1;
    at += chunk.size();
  }
  return at;
}

// The start of a file, up to one of the markers: 64 KiB when that holds one, else up to the
// 16 MiB allowed for text, so that a large file's data are not read twice.
std::string read_head(const BoundedFile& f, std::initializer_list<std::string_view> markers) {
  std::string head = f.read_some(0, 1 << 16);
  const auto found = [&] {
    for (std::string_view m : markers)
      if (head.find(m) != std::string::npos) return true;
    return false;
  };
  if (head.size() < f.size() && !found()) head = f.read_some(0, kMaxTextInputBytes);
  return head;
}

// The file's size must be what `bytes` of data need: not a byte more or less.
void check_raw_size(uint64_t have, uint64_t need, const std::string& where, UVec3 d, SampleType t,
                    const char* field) {
  if (have != need) size_mismatch(where, d, t, have, field);
}

}  // namespace

void set_samples(ScalarVolume& v, std::span<const double> raw, const std::string& where) {
  store(
      v, raw.size(), [&](size_t i) { return raw[i]; }, where);
}

SampleType parse_sample_type(const std::string& name) {
  static const std::map<std::string, SampleType> m = {
      {"uint8", SampleType::u8},    {"u8", SampleType::u8},      {"int8", SampleType::i8},
      {"i8", SampleType::i8},       {"uint16", SampleType::u16}, {"u16", SampleType::u16},
      {"int16", SampleType::i16},   {"i16", SampleType::i16},    {"uint32", SampleType::u32},
      {"u32", SampleType::u32},     {"int32", SampleType::i32},  {"i32", SampleType::i32},
      {"float32", SampleType::f32}, {"f32", SampleType::f32},    {"float", SampleType::f32},
      {"float64", SampleType::f64}, {"f64", SampleType::f64},    {"double", SampleType::f64}};
  const auto it = m.find(name);
  if (it == m.end())
    throw_invalid("volume", "type", name,
                  "one of uint8, int8, uint16, int16, uint32, int32, "
                  "float32, float64");
  return it->second;
}

size_t sample_bytes(SampleType t) {
  switch (t) {
    case SampleType::u8:
    case SampleType::i8:
      return 1;
    case SampleType::u16:
    case SampleType::i16:
      return 2;
    case SampleType::u32:
    case SampleType::i32:
    case SampleType::f32:
      return 4;
    case SampleType::f64:
      return 8;
  }
  return 1;
}

ScalarVolume load_raw(const std::string& path, UVec3 dims, SampleType type, bool big_endian,
                      Vec3f spacing) {
  const std::string where = "raw volume " + path;
  check_dims(dims, where);
  const BoundedFile f(path, "raw volume");
  check_raw_size(f.size(), data_bytes(dims, type), where, dims, type, "dims");
  const std::string data = f.read(0, f.size(), "dims");
  ScalarVolume v;
  v.dims = dims;
  v.spacing = spacing;
  store_bytes(v, reinterpret_cast<const unsigned char*>(data.data()), voxel_count(dims), type,
              big_endian, where);
  check_spacing(v, where);
  return v;
}

ScalarVolume load_nrrd(const std::string& path) {
  const std::string where = "NRRD " + path;
  const BoundedFile file(path, "NRRD");
  // The header ends at the first blank line (attached data) or with the file (detached header).
  const std::string head = read_head(file, {"\n\n", "\n\r\n"});
  const NrrdHeader h = parse_nrrd_header(head, where);
  if (!h.data_at && file.size() > head.size())
    throw_invalid(where, "header", "longer than 16 MiB", "a header ending with a blank line");
  ScalarVolume v;
  v.dims = h.dims;
  v.spacing = h.spacing;
  v.origin = h.origin;

  std::optional<BoundedFile> detached;
  if (!h.data_file.empty()) {
    const auto dir = std::filesystem::path(path).parent_path();
    detached.emplace((dir / h.data_file).string(), "NRRD data file");
  } else if (!h.data_at) {
    throw_invalid(where, "data file", "missing",
                  "a 'data file:' line, or the data after a blank line ending the header");
  }
  const BoundedFile& data = detached ? *detached : file;
  const std::string dwhere = detached ? where + " (data file " + data.path() + ")" : where;
  uint64_t start = skip_lines(data, detached ? 0 : *h.data_at, h.line_skip, dwhere);
  const uint64_t count = voxel_count(h.dims);
  if (h.encoding == NrrdEncoding::raw) {
    const uint64_t bytes = data_bytes(h.dims, h.type);
    if (h.byte_skip == -1) {  // the data are the file's last bytes
      if (data.size() < checked_add(start, bytes, dwhere, "sizes"))
        size_mismatch(dwhere, h.dims, h.type, data.size() - std::min(start, data.size()), "sizes");
      start = data.size() - bytes;
    } else {
      start = checked_add(start, uint64_t(h.byte_skip), dwhere, "byte skip");
    }
    check_raw_size(data.size() - std::min(start, data.size()), bytes, dwhere, h.dims, h.type,
                   "sizes");
    const std::string payload = data.read(start, bytes, "sizes");
    store_bytes(v, reinterpret_cast<const unsigned char*>(payload.data()), count, h.type,
                h.big_endian, where);
  } else {
    start = checked_add(start, uint64_t(h.byte_skip), dwhere, "byte skip");
    const uint64_t have = data.size() - std::min(start, data.size());
    const uint64_t most = checked_mul(count, kMaxTextBytesPerValue, dwhere, "sizes");
    if (have > most)
      throw_invalid(dwhere, "sizes", h.sizes_text,
                    fmt::format("consistent with the data: {} bytes of text for {} values (at "
                                "most {} bytes a value)",
                                have, count, kMaxTextBytesPerValue));
    const auto vals = numbers(data.read(start, have, "byte skip"));
    if (vals.size() != count)
      throw_invalid(dwhere, "sizes", h.sizes_text,
                    fmt::format("consistent with the data: {} values, the sizes need {}",
                                vals.size(), count));
    set_samples(v, vals, where);
  }
  check_spacing(v, where);
  return v;
}

namespace {

// The attributes of the first `<name ...>` tag at or after `from`, and where the tag ends.
std::map<std::string, std::string> tag_attributes(const std::string& file, const std::string& name,
                                                  const std::string& where, size_t from = 0,
                                                  size_t* end = nullptr) {
  const size_t at = file.find("<" + name, from);
  const size_t close = at == std::string::npos ? at : file.find('>', at);
  if (close == std::string::npos) throw_invalid(where, name, "missing", "a <" + name + "> element");
  if (end) *end = close;
  return xml_attributes(file.substr(at, close - at));
}

// Three numbers, or the default when the attribute is absent.
Vec3f three(const std::map<std::string, std::string>& a, const char* name, Vec3f def,
            const std::string& where) {
  const auto it = a.find(name);
  if (it == a.end()) return def;
  const auto v = numbers(it->second);
  if (v.size() != 3) throw_invalid(where, name, it->second, "three numbers");
  return {float(v[0]), float(v[1]), float(v[2])};
}

// WholeExtent "x0 x1 y0 y1 z0 z1" as whole numbers: each axis holds x1 - x0 + 1 points.
UVec3 extent_dims(const std::string& text, const std::string& where, int64_t lo[3]) {
  std::istringstream in(text);
  std::vector<std::string> w;
  for (std::string x; in >> x;) w.push_back(x);
  if (w.size() != 6) throw_invalid(where, "WholeExtent", text, "six integers");
  uint32_t d[3];
  for (int a = 0; a < 3; ++a) {
    lo[a] = parse_i64(w[size_t(2 * a)], where, "WholeExtent");
    const int64_t hi = parse_i64(w[size_t(2 * a + 1)], where, "WholeExtent");
    if (hi < lo[a])
      throw_invalid(where, "WholeExtent", text, "each upper bound >= its lower bound");
    // hi - lo in unsigned arithmetic cannot wrap for hi >= lo.
    const uint64_t points = checked_add(uint64_t(hi) - uint64_t(lo[a]), 1, where, "WholeExtent");
    d[a] = checked_u32_in(points, 2, 8192, where, "WholeExtent (points per axis)");
  }
  return {d[0], d[1], d[2]};
}

}  // namespace

ScalarVolume load_vti(const std::string& path, const std::string& array) {
  const std::string where = "VTI " + path;
  const BoundedFile f(path, "VTI");
  // The extent is declared near the start: read that far first, to bound the whole file by it.
  const std::string start = read_head(f, {"<Piece"});
  if (start.find("<VTKFile") == std::string::npos)
    throw_invalid(where, "VTKFile", "missing", "a VTK XML file");
  auto head = tag_attributes(start, "VTKFile", where);
  if (head["type"] != "ImageData") throw_invalid(where, "type", head["type"], "ImageData");
  if (!head["compressor"].empty())
    throw_invalid(where, "compressor", head["compressor"], "none (save uncompressed)");
  if (!head["byte_order"].empty() && head["byte_order"] != "LittleEndian" &&
      head["byte_order"] != "BigEndian")
    throw_invalid(where, "byte_order", head["byte_order"], "LittleEndian or BigEndian");
  const bool big = head["byte_order"] == "BigEndian";
  if (!head["header_type"].empty() && head["header_type"] != "UInt32" &&
      head["header_type"] != "UInt64")
    throw_invalid(where, "header_type", head["header_type"], "UInt32 or UInt64");
  const size_t header_bytes = head["header_type"] == "UInt64" ? 8 : 4;
  auto ia = tag_attributes(start, "ImageData", where);
  int64_t lo[3];
  ScalarVolume v;
  v.dims = extent_dims(ia["WholeExtent"], where, lo);
  const uint64_t count = voxel_count(v.dims);
  const uint64_t most = checked_add(checked_mul(count, kMaxTextBytesPerValue, where, "WholeExtent"),
                                    kMaxXmlOverheadBytes, where, "WholeExtent");
  if (f.size() > most)
    throw_invalid(where, "WholeExtent", ia["WholeExtent"],
                  fmt::format("consistent with the file: {} bytes is more than {} values can take",
                              f.size(), count));
  const std::string file = f.read(0, f.size(), "file size");
  if (const auto it = ia.find("Direction");
      it != ia.end() && numbers(it->second) != std::vector<double>{1, 0, 0, 0, 1, 0, 0, 0, 1})
    throw_invalid(where, "Direction", it->second, "1 0 0 0 1 0 0 0 1 (axis-aligned)");
  const auto piece = tag_attributes(file, "Piece", where);
  if (const auto it = piece.find("Extent");
      it != piece.end() && numbers(it->second) != numbers(ia["WholeExtent"]))
    throw_invalid(where, "Piece Extent", it->second, "the WholeExtent (one piece)");
  v.spacing = three(ia, "Spacing", {1, 1, 1}, where);
  const Vec3f org = three(ia, "Origin", {0, 0, 0}, where);
  // Point data sit at the grid points: they are the voxel centres, half a voxel inside the box.
  v.origin = {float(org.x + double(lo[0]) * v.spacing.x - 0.5 * v.spacing.x),
              float(org.y + double(lo[1]) * v.spacing.y - 0.5 * v.spacing.y),
              float(org.z + double(lo[2]) * v.spacing.z - 0.5 * v.spacing.z)};
  size_t at = 0, tag_end = 0;
  std::map<std::string, std::string> da;
  for (;;) {
    at = file.find("<DataArray", at);
    if (at == std::string::npos)
      throw_invalid(where, "array", array.empty() ? "(first)" : array, "a DataArray in the file");
    da = tag_attributes(file, "DataArray", where, at, &tag_end);
    if (array.empty() || da["Name"] == array) break;
    at = tag_end;
  }
  if (!da["NumberOfComponents"].empty() && da["NumberOfComponents"] != "1")
    throw_invalid(where, "NumberOfComponents", da["NumberOfComponents"], "1 (a scalar array)");
  const SampleType type = vtk_type(da["type"], where);
  const std::string format = da["format"];
  const size_t close = file.find("</DataArray>", tag_end);
  const std::string_view inline_data = std::string_view(file).substr(
      tag_end + 1, close == std::string::npos ? std::string::npos : close - tag_end - 1);
  std::vector<uint8_t> bytes;
  if (format == "ascii") {
    const auto vals = numbers(std::string(inline_data));
    if (vals.size() != count)
      throw_invalid(where, "WholeExtent", ia["WholeExtent"],
                    fmt::format("consistent with the data: {} values, the extent needs {}",
                                vals.size(), count));
    set_samples(v, vals, where);
    check_spacing(v, where);
    return v;
  } else if (format == "binary") {
    bytes = base64_decode(inline_data, where);
  } else if (format == "appended") {
    size_t ad_end = 0;
    auto aa = tag_attributes(file, "AppendedData", where, 0, &ad_end);
    const size_t underscore = file.find('_', ad_end);
    if (underscore == std::string::npos)
      throw_invalid(where, "AppendedData", "no '_' marker", "data after an '_'");
    const uint64_t offset = da["offset"].empty() ? 0 : parse_u64(da["offset"], where, "offset");
    const uint64_t from = checked_add(underscore + 1, offset, where, "offset");
    if (from > file.size())
      throw_invalid(where, "offset", da["offset"],
                    fmt::format("inside the file ({} bytes)", file.size()));
    if (aa["encoding"] == "raw") {
      bytes.assign(file.begin() + std::ptrdiff_t(from), file.end());
    } else if (aa["encoding"] == "base64") {
      const size_t end = file.find("</AppendedData>", from);
      bytes = base64_decode(
          std::string_view(file).substr(from, end == std::string::npos ? end : end - from), where);
    } else {
      throw_invalid(where, "AppendedData encoding", aa["encoding"], "raw or base64");
    }
  } else {
    throw_invalid(where, "DataArray format", format, "ascii, binary or appended");
  }
  if (bytes.size() < header_bytes) size_mismatch(where, v.dims, type, 0, "WholeExtent");
  unsigned char hb[8] = {};
  std::memcpy(hb, bytes.data(), header_bytes);
  if (big) std::reverse(hb, hb + header_bytes);
  uint64_t declared = 0;
  if (header_bytes == 4) {
    uint32_t d32 = 0;
    std::memcpy(&d32, hb, 4);
    declared = d32;
  } else {
    std::memcpy(&declared, hb, 8);
  }
  if (declared != data_bytes(v.dims, type) || bytes.size() - header_bytes < declared)
    size_mismatch(where, v.dims, type, std::min<uint64_t>(declared, bytes.size() - header_bytes),
                  "WholeExtent");
  store_bytes(v, bytes.data() + header_bytes, count, type, big, where);
  check_spacing(v, where);
  return v;
}

VolumeDesc volume_desc(const ScalarVolume& v) {
  VolumeDesc d;
  d.dims = v.dims;
  d.box_min = v.origin;
  d.box_max = {v.origin.x + v.spacing.x * v.dims.x, v.origin.y + v.spacing.y * v.dims.y,
               v.origin.z + v.spacing.z * v.dims.z};
  const double lo = v.normalised ? 0.0 : v.min, hi = v.normalised ? 1.0 : v.max;
  if (hi > lo) {
    d.value_min = float(lo);
    d.value_max = float(hi);
  } else {
    // Constant c, held as it is (fits_fp32: |c| in [2^-64, 2^64], or 0): c at the top of
    // [c - |c|, c]. A normalised constant holds 1 in [0, 1], the same place.
    const double c = lo;
    d.value_min = c == 0 ? 0.0f : float(c - std::abs(c));
    d.value_max = c == 0 ? 1.0f : float(c);
  }
  return d;
}

}  // namespace masav::volume

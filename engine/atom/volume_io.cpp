#include "engine/atom/volume_io.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "engine/core/error.h"

namespace masav::atom {
namespace {

std::string read_all(const std::string& path, const char* what) {
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw Error("", what, fmt::format("cannot read '{}'", path), "give a readable file");
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

uint64_t voxel_count(UVec3 d) { return uint64_t(d.x) * d.y * d.z; }

void check_dims(UVec3 d, const std::string& where) {
  for (uint32_t v : {d.x, d.y, d.z})
    if (v < 2 || v > 8192)
      throw_invalid(where, "dims", fmt::format("{}x{}x{}", d.x, d.y, d.z), "each in [2, 8192]");
}

template <class T>
float load_one(const unsigned char* p, bool swap) {
  unsigned char b[sizeof(T)];
  std::memcpy(b, p, sizeof(T));
  if (swap) std::reverse(b, b + sizeof(T));
  T v;
  std::memcpy(&v, b, sizeof(T));
  return float(v);
}

std::vector<float> convert(const unsigned char* data, size_t count, SampleType t, bool swap) {
  std::vector<float> out(count);
  const size_t sb = sample_bytes(t);
  for (size_t i = 0; i < count; ++i) {
    const unsigned char* p = data + i * sb;
    switch (t) {
      case SampleType::u8: out[i] = load_one<uint8_t>(p, false); break;
      case SampleType::i8: out[i] = load_one<int8_t>(p, false); break;
      case SampleType::u16: out[i] = load_one<uint16_t>(p, swap); break;
      case SampleType::i16: out[i] = load_one<int16_t>(p, swap); break;
      case SampleType::u32: out[i] = load_one<uint32_t>(p, swap); break;
      case SampleType::i32: out[i] = load_one<int32_t>(p, swap); break;
      case SampleType::f32: out[i] = load_one<float>(p, swap); break;
      case SampleType::f64: out[i] = load_one<double>(p, swap); break;
    }
  }
  return out;
}

void finish(ScalarVolume& v, const std::string& where) {
  size_t bad = 0;
  v.min = INFINITY;
  v.max = -INFINITY;
  for (float x : v.values) {
    if (!std::isfinite(x)) {
      ++bad;
      continue;
    }
    v.min = std::min(v.min, x);
    v.max = std::max(v.max, x);
  }
  if (bad)
    throw Error("", where, fmt::format("{} samples are NaN or infinite", bad),
                "give a volume of finite values");
  for (float s : {v.spacing.x, v.spacing.y, v.spacing.z})
    if (!std::isfinite(s) || !(s > 0))
      throw_invalid(where, "spacing", fmt::format("({}, {}, {})", v.spacing.x, v.spacing.y, v.spacing.z),
                    "finite and > 0 on every axis");
}

void size_mismatch(const std::string& where, UVec3 d, SampleType t, size_t have) {
  throw_invalid(where, "dims", fmt::format("{}x{}x{}", d.x, d.y, d.z),
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
    while (start > 0 && (std::isalnum(static_cast<unsigned char>(tag[start - 1])) || tag[start - 1] == '_'))
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
      {"UInt8", SampleType::u8},   {"Int8", SampleType::i8},     {"UInt16", SampleType::u16},
      {"Int16", SampleType::i16},  {"UInt32", SampleType::u32},  {"Int32", SampleType::i32},
      {"Float32", SampleType::f32}, {"Float64", SampleType::f64}};
  const auto it = m.find(t);
  if (it == m.end())
    throw_invalid(where, "DataArray type", t, "one of UInt8, Int8, UInt16, Int16, UInt32, Int32, "
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

}  // namespace

SampleType parse_sample_type(const std::string& name) {
  static const std::map<std::string, SampleType> m = {
      {"uint8", SampleType::u8},   {"u8", SampleType::u8},     {"int8", SampleType::i8},
      {"i8", SampleType::i8},      {"uint16", SampleType::u16}, {"u16", SampleType::u16},
      {"int16", SampleType::i16},  {"i16", SampleType::i16},   {"uint32", SampleType::u32},
      {"u32", SampleType::u32},    {"int32", SampleType::i32}, {"i32", SampleType::i32},
      {"float32", SampleType::f32}, {"f32", SampleType::f32},  {"float", SampleType::f32},
      {"float64", SampleType::f64}, {"f64", SampleType::f64},  {"double", SampleType::f64}};
  const auto it = m.find(name);
  if (it == m.end())
    throw_invalid("volume", "type", name, "one of uint8, int8, uint16, int16, uint32, int32, "
                                          "float32, float64");
  return it->second;
}

size_t sample_bytes(SampleType t) {
  switch (t) {
    case SampleType::u8:
    case SampleType::i8: return 1;
    case SampleType::u16:
    case SampleType::i16: return 2;
    case SampleType::u32:
    case SampleType::i32:
    case SampleType::f32: return 4;
    case SampleType::f64: return 8;
  }
  return 1;
}

ScalarVolume load_raw(const std::string& path, UVec3 dims, SampleType type, bool big_endian,
                      Vec3f spacing) {
  const std::string where = "raw volume " + path;
  check_dims(dims, where);
  const std::string data = read_all(path, "raw volume");
  if (data.size() != voxel_count(dims) * sample_bytes(type))
    size_mismatch(where, dims, type, data.size());
  ScalarVolume v;
  v.dims = dims;
  v.spacing = spacing;
  v.values = convert(reinterpret_cast<const unsigned char*>(data.data()), voxel_count(dims), type,
                     big_endian);
  finish(v, where);
  return v;
}

ScalarVolume load_nrrd(const std::string& path) {
  const std::string where = "NRRD " + path;
  const std::string file = read_all(path, "NRRD");
  if (file.rfind("NRRD000", 0) != 0)
    throw_invalid(where, "magic", file.substr(0, std::min<size_t>(8, file.size())),
                  "a NRRD file starting with NRRD000x");
  std::map<std::string, std::string> f;
  size_t pos = file.find('\n') + 1, data_at = std::string::npos;
  while (pos < file.size()) {
    const size_t end = file.find('\n', pos);
    std::string line = file.substr(pos, end == std::string::npos ? std::string::npos : end - pos);
    if (!line.empty() && line.back() == '\r') line.pop_back();
    pos = end == std::string::npos ? file.size() : end + 1;
    if (line.empty()) {
      data_at = pos;
      break;
    }
    if (line[0] == '#') continue;
    const size_t colon = line.find(':');
    if (colon == std::string::npos) continue;
    std::string key = line.substr(0, colon), value = line.substr(colon + 1);
    if (!value.empty() && value[0] == '=') value.erase(0, 1);  // key:=value
    value.erase(0, value.find_first_not_of(' '));
    f[key] = value;
  }
  if (!f.count("type")) throw_invalid(where, "type", "missing", "a NRRD type field");
  std::string t = f["type"];
  static const std::map<std::string, std::string> alias = {
      {"uchar", "uint8"},          {"unsigned char", "uint8"},   {"uint8_t", "uint8"},
      {"signed char", "int8"},     {"int8_t", "int8"},           {"short", "int16"},
      {"short int", "int16"},      {"signed short", "int16"},    {"int16_t", "int16"},
      {"ushort", "uint16"},        {"unsigned short", "uint16"}, {"uint16_t", "uint16"},
      {"int", "int32"},            {"signed int", "int32"},      {"int32_t", "int32"},
      {"uint", "uint32"},          {"unsigned int", "uint32"},   {"uint32_t", "uint32"}};
  if (alias.count(t)) t = alias.at(t);
  const SampleType type = parse_sample_type(t);
  const auto sizes = numbers(f["sizes"]);
  if (f["dimension"] != "3" || sizes.size() != 3)
    throw_invalid(where, "dimension", f["dimension"], "3 (a scalar volume)");
  const UVec3 dims{uint32_t(sizes[0]), uint32_t(sizes[1]), uint32_t(sizes[2])};
  check_dims(dims, where);
  ScalarVolume v;
  v.dims = dims;
  if (f.count("spacings")) {
    const auto s = numbers(f["spacings"]);
    if (s.size() == 3) v.spacing = {float(s[0]), float(s[1]), float(s[2])};
  } else if (f.count("space directions")) {
    // Axis-aligned directions: "(sx,0,0) (0,sy,0) (0,0,sz)".
    std::string sd = f["space directions"];
    for (char& c : sd)
      if (c == '(' || c == ')' || c == ',') c = ' ';
    const auto s = numbers(sd);
    if (s.size() == 9) v.spacing = {float(std::abs(s[0])), float(std::abs(s[4])), float(std::abs(s[8]))};
  }
  if (f.count("space origin")) {
    std::string so = f["space origin"];
    for (char& c : so)
      if (c == '(' || c == ')' || c == ',') c = ' ';
    const auto o = numbers(so);
    if (o.size() == 3) v.origin = {float(o[0]), float(o[1]), float(o[2])};
  }
  const std::string enc = f.count("encoding") ? f["encoding"] : "raw";
  std::string payload;
  const std::string detached = f.count("data file") ? f["data file"] : f["datafile"];
  if (!detached.empty()) {
    const auto dir = std::filesystem::path(path).parent_path();
    payload = read_all((dir / detached).string(), "NRRD data file");
  } else {
    if (data_at == std::string::npos) throw_invalid(where, "header", "no blank line", "a NRRD header");
    payload = file.substr(data_at);
  }
  const size_t count = voxel_count(dims);
  if (enc == "raw") {
    if (payload.size() != count * sample_bytes(type)) size_mismatch(where, dims, type, payload.size());
    const bool big = f.count("endian") && f["endian"] == "big";
    v.values = convert(reinterpret_cast<const unsigned char*>(payload.data()), count, type, big);
  } else if (enc == "ascii" || enc == "text" || enc == "txt") {
    const auto vals = numbers(payload);
    if (vals.size() != count)
      throw_invalid(where, "sizes", f["sizes"],
                    fmt::format("consistent with the data: {} values, the sizes need {}",
                                vals.size(), count));
    v.values.assign(vals.begin(), vals.end());
  } else {
    throw_invalid(where, "encoding", enc, "raw or ascii (convert with: unu save -e raw)");
  }
  finish(v, where);
  return v;
}

ScalarVolume load_vti(const std::string& path, const std::string& array) {
  const std::string where = "VTI " + path;
  const std::string file = read_all(path, "VTI");
  const size_t vtk = file.find("<VTKFile");
  if (vtk == std::string::npos) throw_invalid(where, "VTKFile", "missing", "a VTK XML file");
  auto head = xml_attributes(file.substr(vtk, file.find('>', vtk) - vtk));
  if (head["type"] != "ImageData") throw_invalid(where, "type", head["type"], "ImageData");
  if (!head["compressor"].empty())
    throw_invalid(where, "compressor", head["compressor"], "none (save uncompressed)");
  const bool big = head["byte_order"] == "BigEndian";
  const size_t header_bytes = head["header_type"] == "UInt64" ? 8 : 4;
  const size_t img = file.find("<ImageData");
  auto ia = xml_attributes(file.substr(img, file.find('>', img) - img));
  const auto ext = numbers(ia["WholeExtent"]);
  if (ext.size() != 6) throw_invalid(where, "WholeExtent", ia["WholeExtent"], "six integers");
  ScalarVolume v;
  v.dims = {uint32_t(ext[1] - ext[0] + 1), uint32_t(ext[3] - ext[2] + 1), uint32_t(ext[5] - ext[4] + 1)};
  check_dims(v.dims, where);
  const auto sp = numbers(ia["Spacing"]), org = numbers(ia["Origin"]);
  if (sp.size() == 3) v.spacing = {float(sp[0]), float(sp[1]), float(sp[2])};
  // Point data sit at the grid points: they are the voxel centres, half a voxel inside the box.
  if (org.size() == 3)
    v.origin = {float(org[0] + ext[0] * sp[0] - 0.5 * v.spacing.x),
                float(org[1] + ext[2] * sp[1] - 0.5 * v.spacing.y),
                float(org[2] + ext[4] * sp[2] - 0.5 * v.spacing.z)};
  size_t at = 0;
  std::map<std::string, std::string> da;
  size_t tag_end = 0;
  for (;;) {
    at = file.find("<DataArray", at);
    if (at == std::string::npos)
      throw_invalid(where, "array", array.empty() ? "(first)" : array, "a DataArray in the file");
    tag_end = file.find('>', at);
    da = xml_attributes(file.substr(at, tag_end - at));
    if (array.empty() || da["Name"] == array) break;
    at = tag_end;
  }
  if (!da["NumberOfComponents"].empty() && da["NumberOfComponents"] != "1")
    throw_invalid(where, "NumberOfComponents", da["NumberOfComponents"], "1 (a scalar array)");
  const SampleType type = vtk_type(da["type"], where);
  const size_t count = voxel_count(v.dims);
  const std::string format = da["format"];
  std::vector<uint8_t> bytes;
  if (format == "ascii") {
    const size_t close = file.find("</DataArray>", tag_end);
    const auto vals = numbers(file.substr(tag_end + 1, close - tag_end - 1));
    if (vals.size() != count)
      throw_invalid(where, "WholeExtent", ia["WholeExtent"],
                    fmt::format("consistent with the data: {} values, the extent needs {}",
                                vals.size(), count));
    v.values.assign(vals.begin(), vals.end());
    finish(v, where);
    return v;
  } else if (format == "binary") {
    const size_t close = file.find("</DataArray>", tag_end);
    bytes = base64_decode(std::string_view(file).substr(tag_end + 1, close - tag_end - 1), where);
  } else if (format == "appended") {
    const size_t ad = file.find("<AppendedData");
    if (ad == std::string::npos) throw_invalid(where, "AppendedData", "missing", "present");
    auto aa = xml_attributes(file.substr(ad, file.find('>', ad) - ad));
    const size_t start = file.find('_', file.find('>', ad)) + 1;
    const size_t offset = size_t(std::stoull(da["offset"].empty() ? "0" : da["offset"]));
    if (aa["encoding"] == "raw") {
      bytes.assign(file.begin() + std::min(file.size(), start + offset), file.end());
    } else {
      const size_t close = file.find("</AppendedData>", start);
      bytes = base64_decode(std::string_view(file).substr(start + offset, close - start - offset), where);
    }
  } else {
    throw_invalid(where, "DataArray format", format, "ascii, binary or appended");
  }
  if (bytes.size() < header_bytes) size_mismatch(where, v.dims, type, 0);
  uint64_t declared = 0;
  std::memcpy(&declared, bytes.data(), header_bytes);
  if (declared != count * sample_bytes(type) || bytes.size() < header_bytes + declared)
    size_mismatch(where, v.dims, type, size_t(declared));
  v.values = convert(bytes.data() + header_bytes, count, type, big);
  finish(v, where);
  return v;
}

VolumeDesc volume_desc(const ScalarVolume& v) {
  VolumeDesc d;
  d.dims = v.dims;
  d.box_min = v.origin;
  d.box_max = {v.origin.x + v.spacing.x * v.dims.x, v.origin.y + v.spacing.y * v.dims.y,
               v.origin.z + v.spacing.z * v.dims.z};
  d.value_min = v.min;
  d.value_max = v.max > v.min ? v.max : v.min + 1.0f;
  return d;
}

}  // namespace masav::atom

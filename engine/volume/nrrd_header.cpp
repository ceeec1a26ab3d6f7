#include "engine/volume/nrrd_header.h"

#include <fmt/format.h>

#include <cmath>
#include <map>
#include <set>
#include <sstream>
#include <vector>

#include "engine/core/error.h"
#include "engine/util/checked_size.h"

namespace masav::volume {
namespace {

// Fields that describe the data without changing the samples masav reads.
const std::set<std::string>& informational_fields() {
  static const std::set<std::string> s = {"content",
                                          "kinds",
                                          "centers",
                                          "centerings",
                                          "labels",
                                          "units",
                                          "space units",
                                          "sample units",
                                          "min",
                                          "max",
                                          "old min",
                                          "oldmin",
                                          "old max",
                                          "oldmax",
                                          "axis mins",
                                          "axismins",
                                          "axis maxs",
                                          "axismaxs",
                                          "thicknesses",
                                          "space",
                                          "space dimension",
                                          "measurement frame",
                                          "number"};
  return s;
}

const std::set<std::string>& honoured_fields() {
  static const std::set<std::string> s = {
      "type",      "dimension",        "sizes",        "encoding",  "endian",
      "spacings",  "space directions", "space origin", "data file", "datafile",
      "line skip", "lineskip",         "byte skip",    "byteskip"};
  return s;
}

std::vector<std::string> words(std::string_view s) {
  std::vector<std::string> out;
  std::istringstream in{std::string(s)};
  std::string w;
  while (in >> w) out.push_back(w);
  return out;
}

std::vector<double> numbers(std::string s, const std::string& where, const std::string& field) {
  for (char& c : s)
    if (c == '(' || c == ')' || c == ',') c = ' ';
  std::vector<double> v;
  for (const std::string& w : words(s)) {
    size_t used = 0;
    double x = 0;
    try {
      x = std::stod(w, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != w.size()) throw_invalid(where, field, w, "numbers");
    v.push_back(x);
  }
  return v;
}

std::string canonical_type(const std::string& t) {
  static const std::map<std::string, std::string> alias = {{"uchar", "uint8"},
                                                           {"unsigned char", "uint8"},
                                                           {"uint8_t", "uint8"},
                                                           {"signed char", "int8"},
                                                           {"int8_t", "int8"},
                                                           {"short", "int16"},
                                                           {"short int", "int16"},
                                                           {"signed short", "int16"},
                                                           {"signed short int", "int16"},
                                                           {"int16_t", "int16"},
                                                           {"ushort", "uint16"},
                                                           {"unsigned short", "uint16"},
                                                           {"unsigned short int", "uint16"},
                                                           {"uint16_t", "uint16"},
                                                           {"int", "int32"},
                                                           {"signed int", "int32"},
                                                           {"int32_t", "int32"},
                                                           {"uint", "uint32"},
                                                           {"unsigned int", "uint32"},
                                                           {"uint32_t", "uint32"}};
  const auto it = alias.find(t);
  return it == alias.end() ? t : it->second;
}

}  // namespace

NrrdHeader parse_nrrd_header(std::string_view head, const std::string& where) {
  if (head.substr(0, 7) != "NRRD000")
    throw_invalid(where, "magic", std::string(head.substr(0, std::min<size_t>(8, head.size()))),
                  "a NRRD file starting with NRRD000x");
  NrrdHeader h;
  std::map<std::string, std::string> f;
  size_t pos = head.find('\n');
  pos = pos == std::string_view::npos ? head.size() : pos + 1;
  while (pos < head.size()) {
    const size_t end = head.find('\n', pos);
    std::string line(
        head.substr(pos, end == std::string_view::npos ? std::string_view::npos : end - pos));
    if (!line.empty() && line.back() == '\r') line.pop_back();
    pos = end == std::string_view::npos ? head.size() : end + 1;
    if (line.empty()) {
      h.data_at = pos;
      break;
    }
    if (line[0] == '#') continue;
    if (line.find(":=") != std::string::npos) continue;  // key/value pairs: free-form comments
    const size_t colon = line.find(": ");
    if (colon == std::string::npos)
      throw_invalid(where, "header line", line, "\"field: value\", \"key:=value\" or a # comment");
    const std::string key = line.substr(0, colon);
    std::string value = line.substr(colon + 2);
    value.erase(0, value.find_first_not_of(' '));
    if (!honoured_fields().count(key) && !informational_fields().count(key))
      throw_invalid(where, "field", key,
                    "one masav reads (type, dimension, sizes, encoding, endian, spacings, space "
                    "directions, space origin, data file, line skip, byte skip) or one that does "
                    "not change the samples (content, kinds, labels, units, ...)");
    if (!f.emplace(key, value).second)
      throw_invalid(where, key, value,
                    fmt::format("given once (the header has two '{}' lines)", key));
  }
  auto field = [&](const std::string& a, const std::string& b = "") -> const std::string* {
    if (auto it = f.find(a); it != f.end()) return &it->second;
    if (auto it = f.find(b); !b.empty() && it != f.end()) return &it->second;
    return nullptr;
  };

  if (!field("type")) throw_invalid(where, "type", "missing", "a NRRD type field");
  h.type = parse_sample_type(canonical_type(*field("type")));
  if (!field("dimension")) throw_invalid(where, "dimension", "missing", "3 (a scalar volume)");
  if (parse_u64(*field("dimension"), where, "dimension") != 3)
    throw_invalid(where, "dimension", *field("dimension"), "3 (a scalar volume)");
  if (!field("sizes"))
    throw_invalid(where, "sizes", "missing", "three sizes, one per axis (a line 'sizes: X Y Z')");
  h.sizes_text = *field("sizes");
  const auto sizes = words(h.sizes_text);
  if (sizes.size() != 3)
    throw_invalid(where, "sizes", h.sizes_text, "three sizes, one per axis (dimension is 3)");
  uint32_t d[3];
  for (int i = 0; i < 3; ++i)
    d[i] = checked_u32_in(parse_u64(sizes[i], where, "sizes"), 2, 8192, where, "sizes");
  h.dims = {d[0], d[1], d[2]};

  if (const auto* e = field("encoding")) {
    if (*e == "raw")
      h.encoding = NrrdEncoding::raw;
    else if (*e == "ascii" || *e == "text" || *e == "txt")
      h.encoding = NrrdEncoding::ascii;
    else
      throw_invalid(where, "encoding", *e, "raw or ascii (convert with: unu save -e raw)");
  } else {
    throw_invalid(where, "encoding", "missing", "raw or ascii (an 'encoding:' line)");
  }
  if (const auto* e = field("endian")) {
    if (*e != "little" && *e != "big") throw_invalid(where, "endian", *e, "little or big");
    h.big_endian = *e == "big";
  } else if (h.encoding == NrrdEncoding::raw && sample_bytes(h.type) > 1) {
    // NRRD requires the field here; guessing the writer's byte order would read a big-endian
    // file as noise without a word.
    throw_invalid(where, "endian", "missing",
                  fmt::format("little or big: NRRD requires an 'endian:' line for raw {}-byte "
                              "samples (type: {})",
                              sample_bytes(h.type), *field("type")));
  }
  if (const auto* s = field("spacings")) {
    const auto v = numbers(*s, where, "spacings");
    if (v.size() != 3) throw_invalid(where, "spacings", *s, "three numbers");
    h.spacing = {float(v[0]), float(v[1]), float(v[2])};
  }
  if (const auto* s = field("space directions")) {
    if (field("spacings"))
      throw_invalid(where, "space directions", *s,
                    "absent when spacings are given (NRRD allows one)");
    const auto v = numbers(*s, where, "space directions");
    if (v.size() != 9) throw_invalid(where, "space directions", *s, "three vectors (x,y,z)");
    for (int i = 0; i < 9; ++i)
      if (i % 4 != 0 && v[size_t(i)] != 0)
        throw_invalid(where, "space directions", *s,
                      "axis-aligned: (sx,0,0) (0,sy,0) (0,0,sz) (resample rotated volumes first)");
    h.spacing = {float(std::abs(v[0])), float(std::abs(v[4])), float(std::abs(v[8]))};
  }
  if (const auto* s = field("space origin")) {
    const auto v = numbers(*s, where, "space origin");
    if (v.size() != 3) throw_invalid(where, "space origin", *s, "one vector (x,y,z)");
    h.origin = {float(v[0]), float(v[1]), float(v[2])};
  }
  if (const auto* s = field("data file", "datafile")) {
    if (s->empty() || s->rfind("LIST", 0) == 0 || s->find('%') != std::string::npos)
      throw_invalid(where, "data file", *s,
                    "the name of one file (lists and numbered series are not read)");
    h.data_file = *s;
  }
  if (const auto* s = field("line skip", "lineskip"))
    h.line_skip = parse_u64(*s, where, "line skip");
  if (const auto* s = field("byte skip", "byteskip")) {
    h.byte_skip = parse_i64(*s, where, "byte skip");
    if (h.byte_skip < -1) throw_invalid(where, "byte skip", *s, "-1 or a byte count >= 0");
    if (h.byte_skip == -1 && h.encoding != NrrdEncoding::raw)
      throw_invalid(where, "byte skip", *s, "-1 only with raw encoding");
  }
  return h;
}

}  // namespace masav::volume

#include "engine/mesh/mesh_io.h"

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <unordered_map>

#include "engine/core/error.h"
#include "engine/util/bounded_file.h"

namespace masav::mesh {
namespace {

static_assert(std::endian::native == std::endian::little,
              "binary STL is little-endian; reading it on this host needs byte swaps");

constexpr uint64_t kStlHeaderBytes = 84, kStlTriangleBytes = 50;
// A mesh may list more vertices than it uses, but not without bound: three per triangle allows
// every triangle its own.
constexpr uint64_t kMaxVertices = 3 * kMaxTriangles;

const std::string kTriangleLimit = fmt::format("at most {}", kMaxTriangles);

// The lines of a text, with their numbers (from 1) and without the line ending.
class Lines {
 public:
  explicit Lines(std::string_view text) : text_(text) {}
  bool next(std::string_view& line) {
    if (pos_ >= text_.size()) return false;
    size_t end = text_.find('\n', pos_);
    if (end == std::string_view::npos) end = text_.size();
    line = text_.substr(pos_, end - pos_);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    pos_ = end + 1;
    ++number_;
    return true;
  }
  uint64_t number() const { return number_; }

 private:
  std::string_view text_;
  size_t pos_ = 0;
  uint64_t number_ = 0;
};

// The next blank-separated word of `line` (consumed), "" at the end.
std::string_view next_word(std::string_view& line) {
  const size_t start = line.find_first_not_of(" \t\v\f");
  if (start == std::string_view::npos) {
    line = {};
    return {};
  }
  size_t end = line.find_first_of(" \t\v\f", start);
  if (end == std::string_view::npos) end = line.size();
  const std::string_view word = line.substr(start, end - start);
  line.remove_prefix(end);
  return word;
}

std::string at_line(std::string_view where, uint64_t line) {
  return fmt::format("{} line {}", where, line);
}

// A coordinate: the whole word a decimal number (a leading '+' allowed), finite. `where` and
// `field` are called only to name an error (a large file has millions of coordinates).
template <class Where, class Field>
double parse_coordinate(std::string_view word, const Where& where, const Field& field) {
  if (word.empty()) throw_invalid(where(), field(), "(missing)", "a finite number");
  std::string_view digits = word;
  if (digits.size() > 1 && digits[0] == '+' && digits[1] != '-') digits.remove_prefix(1);
  double v = 0;
  const auto [ptr, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), v);
  if (ec == std::errc::result_out_of_range)
    throw_invalid(where(), field(), word, "a finite number (this one overflows a double)");
  if (ec != std::errc() || ptr != digits.data() + digits.size())
    throw_invalid(where(), field(), fmt::format("'{}'", word), "a finite number");
  if (!std::isfinite(v)) throw_invalid(where(), field(), word, "a finite number");
  return v;
}

void check_triangle_count(uint64_t count, const std::string& where) {
  if (count > kMaxTriangles)
    throw_invalid(where, "triangles", std::to_string(count), kTriangleLimit);
}

[[noreturn]] void throw_no_triangles(std::string_view where, size_t vertices,
                                     std::string_view what_lines) {
  throw Error("", std::string(where),
              fmt::format("holds {} vertices and no triangles{}: a mesh needs at least one",
                          vertices, what_lines),
              "give a mesh file with faces (is this the right file?)");
}

// Vertices welded by exact position: the first vertex at a position names it.
class Welder {
 public:
  uint32_t index(TriangleMesh& m, Point p) {
    const Point v{p.x + 0.0, p.y + 0.0, p.z + 0.0};  // -0 and +0 are one position
    const Key k{std::bit_cast<uint64_t>(v.x), std::bit_cast<uint64_t>(v.y),
                std::bit_cast<uint64_t>(v.z)};
    const auto [it, fresh] = map_.try_emplace(k, uint32_t(m.vertices.size()));
    if (fresh) m.vertices.push_back(v);
    return it->second;
  }
  void reserve(size_t n) { map_.reserve(n); }

 private:
  struct Key {
    uint64_t x, y, z;
    bool operator==(const Key&) const = default;
  };
  struct Hash {
    static uint64_t mix(uint64_t z) {  // splitmix64's finaliser
      z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
      z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
      return z ^ (z >> 31);
    }
    size_t operator()(const Key& k) const { return mix(k.x ^ mix(k.y ^ mix(k.z))); }
  };
  std::unordered_map<Key, uint32_t, Hash> map_;
};

uint32_t header_count(std::string_view bytes) {
  uint32_t count = 0;
  std::memcpy(&count, bytes.data() + 80, sizeof(count));
  return count;
}

bool starts_with_solid(std::string_view bytes) {
  const size_t start = bytes.find_first_not_of(" \t\r\n");
  return start != std::string_view::npos && bytes.substr(start, 5) == "solid";
}

uint64_t binary_size(uint64_t count) {
  return kStlHeaderBytes + kStlTriangleBytes * count;
}

TriangleMesh parse_stl_binary(std::string_view bytes, std::string_view where) {
  const uint32_t count = header_count(bytes);
  check_triangle_count(count, std::string(where));
  TriangleMesh m;
  m.triangles.resize(count);
  Welder weld;
  weld.reserve(size_t(count) / 2 + 1);
  for (uint32_t t = 0; t < count; ++t) {
    const char* rec = bytes.data() + kStlHeaderBytes + kStlTriangleBytes * uint64_t(t);
    float xyz[9];
    std::memcpy(xyz, rec + 12, sizeof(xyz));  // after the facet normal, which is recomputed
    for (int k = 0; k < 3; ++k) {
      const Point v{xyz[3 * k], xyz[3 * k + 1], xyz[3 * k + 2]};
      for (int a = 0; a < 3; ++a) {
        const double c = a == 0 ? v.x : a == 1 ? v.y : v.z;
        if (!std::isfinite(c))
          throw_invalid(fmt::format("{} triangle {}", where, t),
                        fmt::format("vertex {} {}", k, "xyz"[a]), fmt::format("{}", c),
                        "a finite number");
      }
      m.triangles[t][k] = weld.index(m, v);
    }
  }
  if (count == 0) throw_no_triangles(where, 0, " (the binary STL header declares 0)");
  return m;
}

TriangleMesh parse_stl_ascii(std::string_view text, std::string_view where, std::string_view note) {
  TriangleMesh m;
  Welder weld;
  Lines lines(text);
  std::string_view line;
  bool seen_solid = false, in_solid = false, in_facet = false;
  int corners = 0;
  std::array<uint32_t, 3> tri{};
  auto unexpected = [&](std::string_view word) {
    throw Error("", at_line(where, lines.number()),
                fmt::format("unexpected '{}'{}: an ASCII STL holds solid, facet normal, outer "
                            "loop, vertex, endloop, endfacet and endsolid lines{}",
                            word, in_facet ? " inside a facet" : "", note),
                "export the mesh again as STL (binary or ASCII)");
  };
  while (lines.next(line)) {
    std::string_view rest = line;
    const std::string_view word = next_word(rest);
    if (word.empty()) continue;
    if (!seen_solid && word != "solid") unexpected(word);
    if (word == "solid") {
      if (in_solid) unexpected(word);
      seen_solid = in_solid = true;
    } else if (word == "endsolid") {
      if (!in_solid || in_facet) unexpected(word);
      in_solid = false;
    } else if (word == "facet") {
      if (!in_solid || in_facet) unexpected(word);
      in_facet = true;
      corners = 0;
    } else if (word == "outer" || word == "endloop") {
      if (!in_facet) unexpected(word);
    } else if (word == "vertex") {
      if (!in_facet) unexpected(word);
      auto here = [&] { return at_line(where, lines.number()); };
      if (corners == 3)
        throw Error("", here(), "a facet with more than 3 vertices",
                    "an STL facet is one triangle: triangulate the mesh before exporting it");
      Point v{};
      v.x = parse_coordinate(next_word(rest), here, [] { return "vertex x"; });
      v.y = parse_coordinate(next_word(rest), here, [] { return "vertex y"; });
      v.z = parse_coordinate(next_word(rest), here, [] { return "vertex z"; });
      if (m.vertices.size() >= kMaxVertices)
        throw_invalid(here(), "vertices", std::to_string(m.vertices.size() + 1),
                      fmt::format("at most {}", kMaxVertices));
      tri[corners++] = weld.index(m, v);
    } else if (word == "endfacet") {
      if (!in_facet) unexpected(word);
      if (corners != 3)
        throw Error("", at_line(where, lines.number()),
                    fmt::format("a facet with {} vertices", corners),
                    "an STL facet is one triangle of 3 vertices");
      if (m.triangles.size() == kMaxTriangles)
        check_triangle_count(m.triangles.size() + 1, at_line(where, lines.number()));
      m.triangles.push_back(tri);
      in_facet = false;
    } else {
      unexpected(word);
    }
  }
  if (in_facet || in_solid)
    throw Error("", std::string(where),
                fmt::format("ends inside a {} (no {} line){}", in_facet ? "facet" : "solid",
                            in_facet ? "endfacet" : "endsolid", note),
                "the file is truncated: export it again");
  if (m.triangles.empty())
    throw_no_triangles(where, m.vertices.size(), fmt::format(" (no facets){}", note));
  return m;
}

}  // namespace

const char* format_name(MeshFormat f) {
  switch (f) {
    case MeshFormat::obj:
      return "OBJ";
    case MeshFormat::stl_binary:
      return "binary STL";
    case MeshFormat::stl_ascii:
      return "ASCII STL";
  }
  return "?";
}

TriangleMesh parse_obj(std::string_view text, std::string_view where) {
  if (text.empty())
    throw Error("", std::string(where), "the file is empty (0 bytes)",
                "give a mesh file with at least one triangle");
  TriangleMesh m;
  Lines lines(text);
  std::string_view line;
  // Positive indices may name vertices listed later; the largest is checked at the end.
  int64_t max_index = 0;
  uint64_t max_index_line = 0;
  std::vector<uint32_t> face;
  while (lines.next(line)) {
    std::string_view rest = line;
    const std::string_view word = next_word(rest);
    auto here = [&] { return at_line(where, lines.number()); };
    if (word == "v") {
      const size_t i = m.vertices.size();
      if (i >= kMaxVertices)
        throw_invalid(here(), "vertices", std::to_string(i + 1),
                      fmt::format("at most {}", kMaxVertices));
      auto field = [&](char axis) {
        return [i, axis] { return fmt::format("vertex {} {}", i + 1, axis); };
      };
      Point v{};
      v.x = parse_coordinate(next_word(rest), here, field('x'));
      v.y = parse_coordinate(next_word(rest), here, field('y'));
      v.z = parse_coordinate(next_word(rest), here, field('z'));
      m.vertices.push_back(v);  // a w or colour after x y z is not used
    } else if (word == "f") {
      auto bad_index = [&](const std::string& value) {
        throw_invalid(here(), "face index", value,
                      fmt::format("from 1 to {0} or from -1 to -{0} (counting back): {0} "
                                  "vertices precede this line",
                                  m.vertices.size()));
      };
      face.clear();
      for (std::string_view ref = next_word(rest); !ref.empty(); ref = next_word(rest)) {
        const std::string_view num = ref.substr(0, ref.find('/'));  // i, i/t, i//n, i/t/n
        int64_t idx = 0;
        const auto [ptr, ec] = std::from_chars(num.data(), num.data() + num.size(), idx);
        if (ec != std::errc() || ptr != num.data() + num.size() || idx == 0)
          bad_index(fmt::format("'{}'", ref));
        if (idx < 0) {
          if (uint64_t(-idx) > m.vertices.size()) bad_index(std::to_string(idx));
          idx = int64_t(m.vertices.size()) + idx + 1;
        } else if (idx > max_index) {
          if (uint64_t(idx) > kMaxVertices) bad_index(std::to_string(idx));
          max_index = idx;
          max_index_line = lines.number();
        }
        face.push_back(uint32_t(idx - 1));
      }
      if (face.size() < 3)
        throw Error("", here(), fmt::format("a face of {} vertices", face.size()),
                    "a face needs at least 3 vertex indices");
      if (m.triangles.size() + face.size() - 2 > kMaxTriangles)
        check_triangle_count(m.triangles.size() + face.size() - 2, here());
      for (size_t k = 1; k + 1 < face.size(); ++k)  // a fan around the first corner
        m.triangles.push_back({face[0], face[k], face[k + 1]});
    }
    // vt, vn, vp, usemtl, mtllib, o, g, s, l, comments: not part of the surface.
  }
  if (uint64_t(max_index) > m.vertices.size())
    throw_invalid(at_line(where, max_index_line), "face index", std::to_string(max_index),
                  fmt::format("from 1 to {0}: the file has {0} vertices", m.vertices.size()));
  if (m.triangles.empty()) throw_no_triangles(where, m.vertices.size(), " (no 'f' lines)");
  return m;
}

TriangleMesh parse_stl(std::string_view bytes, std::string_view where, MeshFormat* format) {
  if (bytes.empty())
    throw Error("", std::string(where), "the file is empty (0 bytes)",
                "give a mesh file with at least one triangle");
  const bool has_header = bytes.size() >= kStlHeaderBytes;
  const uint32_t count = has_header ? header_count(bytes) : 0;
  if (has_header && bytes.size() == binary_size(count)) {
    if (format) *format = MeshFormat::stl_binary;
    return parse_stl_binary(bytes, where);
  }
  if (!starts_with_solid(bytes)) {
    if (!has_header)
      throw Error("", std::string(where),
                  fmt::format("{} bytes: shorter than a binary STL's 84-byte header, and it does "
                              "not start with 'solid' as an ASCII STL does",
                              bytes.size()),
                  "give an STL file (is this the right file?)");
    check_triangle_count(count, fmt::format("{} (binary STL header)", where));
    throw Error("", std::string(where),
                fmt::format("the binary STL header declares {} triangles, which take 84 + 50 x {} "
                            "= {} bytes, but the file holds {} bytes",
                            count, count, binary_size(count), bytes.size()),
                "the file is truncated or its header is wrong: export it again");
  }
  if (format) *format = MeshFormat::stl_ascii;
  const std::string note =
      has_header ? fmt::format(
                       " (read as ASCII because its {} bytes are not the 84 + 50 x {} = "
                       "{} of a binary STL with its header's triangle count)",
                       bytes.size(), count, binary_size(count))
                 : std::string();
  return parse_stl_ascii(bytes, where, note);
}

TriangleMesh read_mesh(const std::string& path, MeshFormat* format) {
  const BoundedFile f(path, "mesh file");  // a directory, FIFO or device is refused here
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  if (ext != ".obj" && ext != ".stl")
    throw Error("", "mesh file",
                fmt::format("'{}' is neither an OBJ nor an STL file by its name", path),
                "give a file whose name ends in .obj or .stl");
  const std::string where = fmt::format("mesh file '{}'", path);
  if (ext == ".stl" && f.size() >= kStlHeaderBytes) {
    // A binary STL's count is checked before its size: a file of 10^8 triangles is refused by
    // the triangle limit, naming it.
    const uint32_t count = header_count(f.read(0, kStlHeaderBytes, "binary STL header"));
    if (f.size() == binary_size(count))
      check_triangle_count(count, fmt::format("{} (binary STL header)", where));
  }
  if (f.size() > kMaxMeshFileBytes)
    throw_invalid(where, "file size", fmt::format("{} bytes", f.size()),
                  fmt::format("at most {} bytes (1 GiB)", kMaxMeshFileBytes));
  const std::string bytes = f.read(0, f.size(), "file size");
  if (ext == ".obj") {
    if (format) *format = MeshFormat::obj;
    return parse_obj(bytes, where);
  }
  return parse_stl(bytes, where, format);
}

}  // namespace masav::mesh

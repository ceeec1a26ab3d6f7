#pragma once
// Triangle meshes read from OBJ and STL files, bounded before they are read. Only regular files
// are opened (engine/util/bounded_file.h: a FIFO, a device or a directory is refused by name), the
// file size and the triangle count are limited before anything is allocated for them, and every
// vertex must be finite and every index in range; each refusal names the file, the line (OBJ) or
// the triangle (STL), the value and what is allowed.
//   OBJ: `v x y z [w]` and `f i j k ...` lines (indices 1-based, negative ones counting back from
//        the last vertex read, `i/t/n` forms allowed); a polygon is split into a fan of
//        triangles. Every other line (vt, vn, usemtl, o, g, s, l, comments) is ignored.
//   STL: binary when the file holds exactly 84 + 50 x the header's triangle count bytes, else
//        ASCII (it must start with "solid"). Vertices of equal position (x, y, z compared
//        exactly, -0 = +0) are welded into one index, so that the triangles share edges.
#include <cstdint>
#include <string>
#include <string_view>

#include "engine/mesh/triangle_mesh.h"

namespace masav::mesh {

// The largest mesh file read: 1 GiB (a binary STL of 10^7 triangles is 500 MB).
inline constexpr uint64_t kMaxMeshFileBytes = uint64_t(1) << 30;

enum class MeshFormat { obj, stl_binary, stl_ascii };
const char* format_name(MeshFormat f);

// The file at `path`, its format chosen by the extension (.obj, .stl; any case). `format`, when
// given, receives the format read. Throws masav::Error.
TriangleMesh read_mesh(const std::string& path, MeshFormat* format = nullptr);

// The parsers, on a file's bytes; `where` names the input in errors ("mesh file 'a.obj'").
TriangleMesh parse_obj(std::string_view text, std::string_view where);
// Binary or ASCII as above.
TriangleMesh parse_stl(std::string_view bytes, std::string_view where,
                       MeshFormat* format = nullptr);

}  // namespace masav::mesh

// `masav mesh FILE`: what masav reads from a triangle-mesh file (OBJ, STL) and whether it bounds
// a solid a boundary can be made of; with --sdf, its signed distance field's grid and range.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "app/commands.h"
#include "app/host_environment.h"
#include "app/number_checks.h"
#include "engine/core/error.h"
#include "engine/mesh/mesh_check.h"
#include "engine/mesh/mesh_io.h"
#include "engine/mesh/sdf_cache.h"

namespace masav::app {
namespace {

struct MeshOptions {
  std::string file;
  double spacing = 0;  // 0: the longest side of the bounds / 64
  double padding = 0;
  bool padding_given = false;
  bool sdf = false;
  uint32_t threads = 0;
};

std::string point(mesh::Point p) {
  return fmt::format("({:.9g}, {:.9g}, {:.9g})", p.x, p.y, p.z);
}

int run_mesh(const MeshOptions& o) {
  mesh::MeshFormat format{};
  const mesh::TriangleMesh m = mesh::read_mesh(o.file, &format);
  const mesh::MeshCheck c = mesh::check_mesh(m);
  fmt::print("mesh {} ({})\n", o.file, mesh::format_name(format));
  fmt::print("  triangles  {}\n  vertices   {}\n", c.triangles, c.vertices);
  fmt::print("  bounds     {} to {}\n", point(c.bounds.lo), point(c.bounds.hi));
  fmt::print("  area       {:.9g}\n  volume     {:.9g}\n", c.area, c.volume);
  const std::string where = fmt::format("mesh file '{}'", o.file);
  if (!c.closed()) throw Error("", where, c.problem, c.remedy);
  fmt::print("  watertight OK (closed, manifold, consistently oriented, facing outward)\n");
  if (!o.sdf && !(o.spacing > 0) && !o.padding_given) return 0;
  const mesh::Point ext = c.bounds.hi - c.bounds.lo;
  mesh::SdfParams p;
  p.spacing = o.spacing > 0 ? o.spacing : std::max({ext.x, ext.y, ext.z}) / 64;
  p.padding = o.padding_given ? o.padding : 2 * p.spacing;
  p.threads = o.threads;
  const mesh::SdfBuild b =
      mesh::load_or_build_sdf(m, p, host_environment().cache_dir().string(), where);
  const auto& f = b.field;
  fmt::print("sdf {} x {} x {} nodes, spacing {:.9g}, padding {:.9g}, origin {}\n", f.dims.x,
             f.dims.y, f.dims.z, f.spacing, p.padding, point(f.origin));
  fmt::print("  min {:.9g}\n  max {:.9g}\n", f.min_value(), f.max_value());
  if (b.from_cache)
    fmt::print("  loaded from the cache {}\n", b.cache_path);
  else
    fmt::print("  built in {:.3f} s{}\n", b.build_s,
               b.cache_path.empty() ? "" : fmt::format(", cached as {}", b.cache_path));
  return 0;
}

}  // namespace

void add_mesh_command(CLI::App& app) {
  static MeshOptions o;
  auto* cmd = add_command(app, "mesh",
                          "read a triangle mesh (OBJ, STL), check that it is a closed solid; "
                          "with --sdf, its signed distance field",
                          o, run_mesh);
  cmd->add_option("file", o.file, "mesh file (.obj, .stl binary or ASCII)")->required();
  cmd->add_flag("--sdf", o.sdf,
                "build the signed distance field (or load it from the cache) and print its grid "
                "and range (implied by --spacing and --padding)");
  cmd->add_option("--spacing", o.spacing,
                  "distance between the field's nodes (0: the longest side of the bounds / 64)")
      ->check(number_in(0, 1e12));
  cmd->add_option("--padding", o.padding,
                  "margin of the field beyond the bounds on each side (0: none; default: 2 x "
                  "the spacing)")
      ->check(number_in(0, 1e12))
      ->each([](const std::string&) { o.padding_given = true; });
  add_ranged_option(*cmd, "--threads", o.threads,
                    "threads building the field (0: one per hardware thread; the field is the "
                    "same for any count)",
                    0u, 256u);
}

}  // namespace masav::app

#include "engine/mesh/sdf_cache.h"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <cstring>

#include "engine/core/error.h"
#include "engine/util/cache_file.h"
#include "engine/util/checksum.h"

namespace masav::mesh {
namespace {

constexpr uint32_t kPayloadVersion = 1;

std::string cache_key(const TriangleMesh& m, const SdfParams& p, const SdfGrid& g) {
  return fmt::format(
      "mesh={:016x} vertices={} triangles={} spacing={:a} padding={:a} origin=({:a},{:a},{:a}) "
      "dims={}x{}x{}",
      sdf_content_hash(m, p), m.vertices.size(), m.triangles.size(), p.spacing, p.padding,
      g.origin.x, g.origin.y, g.origin.z, g.dims.x, g.dims.y, g.dims.z);
}

// "" when every value is a distance the grid can hold: finite, and no farther than the grid's
// diagonal (every node lies in the box that holds the mesh, so the mesh is nearer than that).
std::string implausible_value(const SignedDistanceField& f) {
  const double diag =
      f.spacing * std::sqrt(double(f.dims.x) * f.dims.x + double(f.dims.y) * f.dims.y +
                            double(f.dims.z) * f.dims.z);
  for (size_t i = 0; i < f.values.size(); ++i)
    if (!std::isfinite(f.values[i]) || std::fabs(f.values[i]) > diag)
      return fmt::format("node {} holds {}, not a distance within this grid (at most {})", i,
                         f.values[i], diag);
  return "";
}

}  // namespace

uint64_t sdf_content_hash(const TriangleMesh& m, const SdfParams& p) {
  uint64_t h = fnv1a64("masav mesh sdf 1");
  const uint64_t counts[2] = {m.vertices.size(), m.triangles.size()};
  h = fnv1a64(counts, sizeof(counts), h);
  h = fnv1a64(m.vertices.data(), m.vertices.size() * sizeof(Point), h);
  h = fnv1a64(m.triangles.data(), m.triangles.size() * sizeof(m.triangles[0]), h);
  const double params[2] = {p.spacing, p.padding};
  return fnv1a64(params, sizeof(params), h);
}

std::string sdf_cache_path(const TriangleMesh& m, const SdfParams& p,
                           const std::string& cache_dir) {
  if (cache_dir.empty()) return "";
  return fmt::format("{}/mesh-sdf/{:016x}.bin", cache_dir, sdf_content_hash(m, p));
}

SdfBuild load_or_build_sdf(const TriangleMesh& m, const SdfParams& p, const std::string& cache_dir,
                           std::string_view where) {
  const SdfGrid g = sdf_grid(m.bounds(), p);
  SdfBuild r;
  r.cache_path = sdf_cache_path(m, p, cache_dir);
  const CacheFileId id{"mesh-sdf", kPayloadVersion, cache_key(m, p, g)};
  const uint64_t bytes = g.nodes() * sizeof(double);
  if (!r.cache_path.empty()) {
    CacheRead read = read_cache_file(r.cache_path, id, bytes);
    r.rejected = read.rejected;
    if (read.payload && read.payload->size() != bytes)
      r.rejected = fmt::format("payload of {} bytes, not the {} of a {}x{}x{} grid",
                               read.payload->size(), bytes, g.dims.x, g.dims.y, g.dims.z);
    if (read.payload && r.rejected.empty()) {
      SignedDistanceField f{g.origin, p.spacing, g.dims, std::vector<double>(g.nodes())};
      std::memcpy(f.values.data(), read.payload->data(), bytes);
      r.rejected = implausible_value(f);
      if (r.rejected.empty()) {
        r.field = std::move(f);
        r.from_cache = true;
        return r;
      }
    }
    if (!r.rejected.empty()) note_cache_rejected(r.cache_path, r.rejected);
  }
  const auto t0 = std::chrono::steady_clock::now();
  r.field = build_sdf(m, p, where);
  r.build_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (!r.cache_path.empty()) {
    try {
      write_cache_file(
          r.cache_path, id,
          std::string_view(reinterpret_cast<const char*>(r.field.values.data()), bytes));
    } catch (const Error&) {
      // An unwritable cache costs a recomputation next time, nothing else.
    }
  }
  return r;
}

}  // namespace masav::mesh

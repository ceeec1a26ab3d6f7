#pragma once
// Signed distance fields cached on disk, keyed by a hash of the mesh and the field's parameters.
// A file lives at <cache_dir>/mesh-sdf/<hash>.bin in the checked cache envelope
// (engine/util/cache_file.h: magic and version, the full key with the hash, the grid's origin and
// dims, the payload's size and checksum; written to a temporary name and renamed). On load the
// header, the size and the checksum must match and every value must be a distance this grid can
// hold; a file that does not is rebuilt and rewritten, never used. cache_dir "" caches nothing:
// the library never reads the environment, the program passes the directory.
#include <cstdint>
#include <string>

#include "engine/mesh/mesh_sdf.h"

namespace masav::mesh {

// 64-bit FNV-1a of the mesh (every vertex's and index's bits, the counts) and of the spacing and
// padding (not the thread count, which changes no value).
uint64_t sdf_content_hash(const TriangleMesh& m, const SdfParams& p);
// "" when cache_dir is "".
std::string sdf_cache_path(const TriangleMesh& m, const SdfParams& p, const std::string& cache_dir);

struct SdfBuild {
  SignedDistanceField field;
  bool from_cache = false;  // loaded, not computed
  std::string cache_path;   // "" without a cache directory
  std::string rejected;     // why an existing cache file was not used ("" when none was refused)
  double build_s = 0;       // seconds spent computing (0 when loaded)
};

// The field from the cache when a valid file is there, else computed and (when cache_dir is not
// "") written; a cache that cannot be written costs a recomputation next time, nothing else.
SdfBuild load_or_build_sdf(const TriangleMesh& m, const SdfParams& p, const std::string& cache_dir,
                           std::string_view where = "mesh sdf");

}  // namespace masav::mesh

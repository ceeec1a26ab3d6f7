#pragma once
// The scattering table as the scene uses it: computed by scatter_table on a backend, cached on
// disk keyed by every parameter (written to a temporary name and renamed), exported as CSV, and
// turned into the phase table nebula_view reads.
#include <optional>
#include <string>
#include <vector>

#include "engine/kernels/backend.h"

namespace masav::atom {

struct ScatterTable {
  ScatterTableParams params;
  std::vector<double> weight;  // rows x (bins + kScatterExtras) weight fractions
  std::vector<uint32_t> hits;  // photons per entry
  std::string backend;         // the backend that computed it (informational)
  double compute_ms = 0;       // 0 when loaded from the cache
};

// Every parameter, in a canonical text form (floats as exact hex), and its 64-bit FNV-1a hash.
std::string scatter_cache_key(const ScatterTableParams& p);
// <dir>/scatter/<hash>.bin, dir the cache directory (engine/util/cache_dir.h); "" when dir is ""
// (no cache): then nothing is loaded, and saving throws.
std::string scatter_cache_path(const ScatterTableParams& p, const std::string& dir = "");

ScatterTable compute_scatter_table(Backend& b, const ScatterTableParams& p);
// The file names its format version and full key and holds a checksum of its payload; a file
// that does not match, or holds a value no computation could give (not finite, a weight outside
// [0, 1], more hits than photons), is ignored with a note on stderr, never trusted.
std::optional<ScatterTable> load_scatter_cache(const ScatterTableParams& p,
                                               const std::string& dir = "");
void save_scatter_cache(const ScatterTable& t, const std::string& dir = "");
// Loads the table from the cache, or computes and caches it; `hit` says which.
ScatterTable scatter_table_cached(Backend& b, const ScatterTableParams& p,
                                  const std::string& dir = "", bool* hit = nullptr);

// rows x bins: the scattered part of each bin (the forward bin less the unscattered photons),
// in double before any rounding to fp32.
std::vector<double> make_phase_table(const ScatterTable& t);
// Columns: tau, then one per bin (named by the bin's centre cos theta), then the extras.
void write_scatter_csv(const ScatterTable& t, const std::string& path);

}  // namespace masav::atom

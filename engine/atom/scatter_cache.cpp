#include "engine/atom/scatter_cache.h"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>

#include "engine/core/error.h"
#include "engine/io/csv_writer.h"
#include "engine/util/cache_file.h"
#include "engine/util/checked_size.h"
#include "engine/util/checksum.h"

namespace masav::atom {
namespace {

// The payload: the backend's name and a newline, then rows x (bins + extras) weights (double),
// then as many photon counts (uint32), in the host's byte order.
constexpr uint32_t kPayloadVersion = 2;
constexpr uint64_t kMaxBackendName = 64;
constexpr uint64_t kEntryBytes = sizeof(double) + sizeof(uint32_t);

uint64_t entries(const ScatterTableParams& p) {
  return checked_mul(p.rows, uint64_t(p.bins) + kScatterExtras, "scatter table", "rows x bins");
}

CacheFileId cache_id(const ScatterTableParams& p) {
  return {"scatter-table", kPayloadVersion, scatter_cache_key(p)};
}

// "" when every entry is a possible result of these parameters: a weight is a fraction of the
// photons' weight (finite, in [0, 1]) and a count at most the photons traced per row.
std::string implausible_entry(const ScatterTable& t) {
  for (size_t i = 0; i < t.weight.size(); ++i)
    if (!std::isfinite(t.weight[i]) || t.weight[i] < 0 || t.weight[i] > 1 + 1e-6)
      return fmt::format("entry {} holds weight {}, outside [0, 1]", i, t.weight[i]);
  for (size_t i = 0; i < t.hits.size(); ++i)
    if (t.hits[i] > t.params.photons_per_row)
      return fmt::format("entry {} counts {} photons, more than the {} traced per row", i,
                         t.hits[i], t.params.photons_per_row);
  return "";
}

}  // namespace

std::string scatter_cache_key(const ScatterTableParams& p) {
  return fmt::format(
      "rows={} first_row={} bins={} tau_step={:a} g={:a} albedo={:a} threshold={:a} "
      "photons_per_row={} max_scatterings={} start={} direction=({:a},{:a},{:a}) seed={}",
      p.rows, p.first_row, p.bins, p.tau_step, p.g, p.albedo, p.weight_threshold, p.photons_per_row,
      p.max_scatterings, p.start == ScatterStart::centre ? "centre" : "surface", p.direction.x,
      p.direction.y, p.direction.z, p.seed);
}

std::string scatter_cache_path(const ScatterTableParams& p, const std::string& dir) {
  if (dir.empty()) return "";
  return fmt::format("{}/scatter/{:016x}.bin", dir, fnv1a64(scatter_cache_key(p)));
}

ScatterTable compute_scatter_table(Backend& b, const ScatterTableParams& p) {
  auto table = b.create<Real>(entries(p), "scatter table");
  auto hits = b.create<uint32_t>(entries(p), "scatter hits");
  const auto t0 = std::chrono::steady_clock::now();
  b.scatter_table(p, table, hits);
  ScatterTable t{p, b.download(table), b.download(hits), b.name(), 0};
  t.compute_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return t;
}

std::optional<ScatterTable> load_scatter_cache(const ScatterTableParams& p,
                                               const std::string& dir) {
  const std::string path = scatter_cache_path(p, dir);
  if (path.empty()) return std::nullopt;
  const uint64_t n = entries(p);
  auto payload = load_cache_file(path, cache_id(p), kMaxBackendName + 1 + n * kEntryBytes);
  if (!payload) return std::nullopt;
  const size_t eol = payload->find('\n');
  if (eol == std::string::npos || eol > kMaxBackendName ||
      payload->size() != eol + 1 + n * kEntryBytes) {
    note_cache_rejected(path, "payload of the wrong size for these parameters");
    return std::nullopt;
  }
  ScatterTable t{p, std::vector<double>(n), std::vector<uint32_t>(n), payload->substr(0, eol), 0};
  std::memcpy(t.weight.data(), payload->data() + eol + 1, n * sizeof(double));
  std::memcpy(t.hits.data(), payload->data() + eol + 1 + n * sizeof(double), n * sizeof(uint32_t));
  if (const std::string bad = implausible_entry(t); !bad.empty()) {
    note_cache_rejected(path, bad);
    return std::nullopt;
  }
  return t;
}

void save_scatter_cache(const ScatterTable& t, const std::string& dir) {
  const std::string path = scatter_cache_path(t.params, dir);
  if (path.empty())
    throw Error("", "cache", "no cache directory for the scattering table",
                "pass a cache directory (AtomSceneOptions::cache_dir; the masav command line "
                "takes MASAV_CACHE_DIR or HOME)");
  std::string payload = t.backend.substr(0, kMaxBackendName) + "\n";
  const size_t head = payload.size();
  payload.resize(head + t.weight.size() * sizeof(double) + t.hits.size() * sizeof(uint32_t));
  std::memcpy(payload.data() + head, t.weight.data(), t.weight.size() * sizeof(double));
  std::memcpy(payload.data() + head + t.weight.size() * sizeof(double), t.hits.data(),
              t.hits.size() * sizeof(uint32_t));
  write_cache_file(path, cache_id(t.params), payload);
}

ScatterTable scatter_table_cached(Backend& b, const ScatterTableParams& p, const std::string& dir,
                                  bool* hit) {
  if (auto t = load_scatter_cache(p, dir)) {
    if (hit) *hit = true;
    return *t;
  }
  if (hit) *hit = false;
  ScatterTable t = compute_scatter_table(b, p);
  try {
    save_scatter_cache(t, dir);
  } catch (const Error&) {
    // An unwritable cache costs a recomputation next time, nothing else.
  }
  return t;
}

std::vector<double> make_phase_table(const ScatterTable& t) {
  const ScatterTableParams& p = t.params;
  const uint32_t stride = p.bins + kScatterExtras;
  std::vector<double> out(size_t(p.rows) * p.bins);
  for (uint32_t r = 0; r < p.rows; ++r)
    for (uint32_t b = 0; b < p.bins; ++b) {
      double v = t.weight[r * stride + b];
      if (b + 1 == p.bins) v -= t.weight[r * stride + p.bins + kScatterUnscattered];
      out[size_t(r) * p.bins + b] = std::max(v, 0.0);
    }
  return out;
}

void write_scatter_csv(const ScatterTable& t, const std::string& path) {
  const ScatterTableParams& p = t.params;
  std::vector<std::string> cols = {"tau"};
  for (uint32_t b = 0; b < p.bins; ++b)
    cols.push_back(fmt::format("cos_{:.4f}", -1.0 + (b + 0.5) * 2.0 / p.bins));
  cols.insert(cols.end(), {"capped", "below_threshold", "unscattered"});
  CsvWriter csv(cols);
  const uint32_t stride = p.bins + kScatterExtras;
  for (uint32_t r = 0; r < p.rows; ++r) {
    std::vector<double> row = {double(p.first_row + r) * double(p.tau_step)};
    row.insert(row.end(), t.weight.begin() + r * stride, t.weight.begin() + (r + 1) * stride);
    csv.row(row);
  }
  csv.write(path);
}

}  // namespace masav::atom

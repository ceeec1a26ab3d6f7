#include "engine/atom/scatter_cache.h"

#include <fmt/format.h>

#include <chrono>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>

#include "engine/core/error.h"
#include "engine/io/csv_writer.h"
#include "engine/util/json_writer.h"

namespace masav::atom {
namespace {

constexpr const char* kMagic = "masav-scatter-table v1";

uint64_t fnv1a(const std::string& s) {
  uint64_t h = 0xcbf29ce484222325ull;
  for (unsigned char c : s) h = (h ^ c) * 0x100000001b3ull;
  return h;
}

std::string cache_dir(const std::string& dir) {
  if (!dir.empty()) return dir;
  if (const char* d = std::getenv("MASAV_CACHE_DIR")) return d;
  if (const char* x = std::getenv("XDG_CACHE_HOME")) return std::string(x) + "/masav";
  if (const char* h = std::getenv("HOME")) return std::string(h) + "/.cache/masav";
  return ".masav-cache";
}

size_t entries(const ScatterTableParams& p) { return size_t(p.rows) * (p.bins + kScatterExtras); }

}  // namespace

std::string scatter_cache_key(const ScatterTableParams& p) {
  return fmt::format(
      "rows={} first_row={} bins={} tau_step={:a} g={:a} albedo={:a} threshold={:a} "
      "photons_per_row={} max_scatterings={} start={} direction=({:a},{:a},{:a}) seed={}",
      p.rows, p.first_row, p.bins, p.tau_step, p.g, p.albedo, p.weight_threshold,
      p.photons_per_row, p.max_scatterings, p.start == ScatterStart::centre ? "centre" : "surface",
      p.direction.x, p.direction.y, p.direction.z, p.seed);
}

std::string scatter_cache_path(const ScatterTableParams& p, const std::string& dir) {
  return fmt::format("{}/scatter/{:016x}.bin", cache_dir(dir), fnv1a(scatter_cache_key(p)));
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

std::optional<ScatterTable> load_scatter_cache(const ScatterTableParams& p, const std::string& dir) {
  std::ifstream in(scatter_cache_path(p, dir), std::ios::binary);
  if (!in) return std::nullopt;
  std::string magic, key, backend;
  if (!std::getline(in, magic) || magic != kMagic) return std::nullopt;
  if (!std::getline(in, key) || key != scatter_cache_key(p)) return std::nullopt;
  if (!std::getline(in, backend)) return std::nullopt;
  ScatterTable t{p, std::vector<double>(entries(p)), std::vector<uint32_t>(entries(p)), backend, 0};
  in.read(reinterpret_cast<char*>(t.weight.data()), std::streamsize(t.weight.size() * 8));
  in.read(reinterpret_cast<char*>(t.hits.data()), std::streamsize(t.hits.size() * 4));
  if (!in || in.peek() != std::char_traits<char>::eof()) return std::nullopt;
  return t;
}

void save_scatter_cache(const ScatterTable& t, const std::string& dir) {
  std::string body = fmt::format("{}\n{}\n{}\n", kMagic, scatter_cache_key(t.params), t.backend);
  const size_t head = body.size();
  body.resize(head + t.weight.size() * 8 + t.hits.size() * 4);
  std::memcpy(body.data() + head, t.weight.data(), t.weight.size() * 8);
  std::memcpy(body.data() + head + t.weight.size() * 8, t.hits.data(), t.hits.size() * 4);
  write_file_atomic(scatter_cache_path(t.params, dir), body);
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

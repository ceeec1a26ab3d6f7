// scatter_table on every backend: the invariants of thesis §2.2.3's Monte Carlo (albedo 1 loses
// no weight, tau -> 0 sends everything forward), single scattering against the Henyey-Greenstein
// phase function and against an independent quadrature, reproducible rows, the CPU reference
// matched by a chi-square test, and bad input.
#include <doctest/doctest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <vector>

#include "engine/atom/quadrature.h"
#include "engine/atom/scatter_cache.h"
#include "engine/atom/scatter_reference.h"
#include "engine/core/error.h"
#include "engine/util/cache_file.h"
#include "tests/backend_fixture.h"

using namespace masav;

namespace {

struct Table {
  ScatterTableParams p;
  std::vector<double> weight;
  std::vector<uint32_t> hits;
  uint32_t stride() const { return p.bins + kScatterExtras; }
  double w(uint32_t row, uint32_t e) const { return weight[row * stride() + e]; }
  uint32_t h(uint32_t row, uint32_t e) const { return hits[row * stride() + e]; }
};

Table run_table(Backend& b, const ScatterTableParams& p) {
  const size_t n = size_t(p.rows) * (p.bins + kScatterExtras);
  auto table = b.create<Real>(n, "table");
  auto hits = b.create<uint32_t>(n, "hits");
  b.scatter_table(p, table, hits);
  return Table{p, b.download(table), b.download(hits)};
}

double hg_cdf(double g, double x) {  // P(cos theta <= x) of Henyey-Greenstein
  if (std::abs(g) < 1e-9) return 0.5 * (x + 1);
  return (1 - g * g) / (2 * g) * (1 / std::sqrt(1 + g * g - 2 * g * x) - 1 / (1 + g));
}

double chi_critical(int dof) {  // p = 1e-4, Wilson-Hilferty
  const double z = 3.719, k = dof;
  const double t = 1.0 - 2.0 / (9.0 * k) + z * std::sqrt(2.0 / (9.0 * k));
  return k * t * t * t;
}

// Pearson chi-square of observed counts against expected ones (pooling expected < 5).
double chi_square(const std::vector<double>& obs, const std::vector<double>& expect, int& dof) {
  double chi = 0, po = 0, pe = 0;
  dof = -1;
  for (size_t i = 0; i < obs.size(); ++i) {
    if (expect[i] < 5) {
      po += obs[i];
      pe += expect[i];
      continue;
    }
    chi += (obs[i] - expect[i]) * (obs[i] - expect[i]) / expect[i];
    ++dof;
  }
  if (pe > 0) chi += (po - pe) * (po - pe) / std::max(pe, 1.0), ++dof;
  return chi;
}

}  // namespace

TEST_CASE("scatter_table: albedo 1 loses no weight; the event cap is accounted for") {
  ScatterTableParams p;
  p.rows = 4;
  p.tau_step = 1.0f;  // tau = 0, 1, 2, 3
  p.albedo = 1.0f;
  p.photons_per_row = 2048;
  p.max_scatterings = 2000;
  const Table t = run_table(test::backend(), p);
  for (uint32_t r = 0; r < p.rows; ++r) {
    CAPTURE(r);
    double escaped = 0;
    for (uint32_t b = 0; b < p.bins; ++b) escaped += t.w(r, b);
    CHECK(t.h(r, p.bins + kScatterThreshold) == 0);
    CHECK(t.h(r, p.bins + kScatterCapped) == 0);
    CHECK(escaped == doctest::Approx(1.0).epsilon(1e-6));
  }
  p.max_scatterings = 3;  // now many photons are cut: the cut weight is counted apart
  const Table c = run_table(test::backend(), p);
  CHECK(c.h(3, p.bins + kScatterCapped) > 100);
  for (uint32_t r = 0; r < p.rows; ++r) {
    double total = c.w(r, p.bins + kScatterCapped);
    for (uint32_t b = 0; b < p.bins; ++b) total += c.w(r, b);
    CHECK(total == doctest::Approx(1.0).epsilon(1e-6));
  }
}

TEST_CASE("scatter_table: tau -> 0 sends all weight forward") {
  ScatterTableParams p;
  p.rows = 2;
  p.tau_step = 1e-3f;  // tau = 0 and 0.001
  p.photons_per_row = 4096;
  const Table t = run_table(test::backend(), p);
  const uint32_t fwd = p.bins - 1;
  CHECK(t.h(0, fwd) == p.photons_per_row);
  CHECK(t.h(0, p.bins + kScatterUnscattered) == p.photons_per_row);
  CHECK(t.w(0, fwd) == doctest::Approx(1.0).epsilon(1e-6));
  // Unscattered fraction e^{-2 tau} = 0.998; the forward bin also gets some scattered weight.
  CHECK(t.w(1, fwd) >= 0.995);
  CHECK(t.w(1, p.bins + kScatterUnscattered) == doctest::Approx(std::exp(-2e-3)).epsilon(2e-3));
}

TEST_CASE("scatter_table: single scattering follows the Henyey-Greenstein phase function") {
  ScatterTableParams p;
  p.rows = 1;
  p.first_row = 1;
  p.tau_step = 0.005f;
  p.start = ScatterStart::centre;
  p.max_scatterings = 1;
  p.weight_threshold = 0;
  p.photons_per_row = 1u << 18;
  p.g = 0.6f;
  const Table t = run_table(test::backend(), p);
  std::vector<double> obs(p.bins), expect(p.bins);
  double scattered = 0;
  for (uint32_t b = 0; b < p.bins; ++b) {
    obs[b] = t.h(0, b) - (b == p.bins - 1 ? t.h(0, p.bins + kScatterUnscattered) : 0);
    scattered += obs[b];
  }
  CHECK(scattered > 1000);
  for (uint32_t b = 0; b < p.bins; ++b)
    expect[b] =
        scattered * (hg_cdf(p.g, -1 + 2.0 * (b + 1) / p.bins) - hg_cdf(p.g, -1 + 2.0 * b / p.bins));
  int dof;
  const double chi = chi_square(obs, expect, dof);
  CAPTURE(dof);
  CHECK(chi < chi_critical(dof));
}

TEST_CASE("scatter_table: single scattering equals an independent quadrature") {
  for (double tau : {0.3, 1.5}) {
    CAPTURE(tau);
    ScatterTableParams p;
    p.rows = 1;
    p.first_row = 1;
    p.tau_step = float(tau);
    p.max_scatterings = 1;  // photons that would scatter twice are cut: exactly single scattering
    p.weight_threshold = 0;
    p.photons_per_row = 1u << 16;
    const Table t = run_table(test::backend(), p);
    const double tf = double(float(tau));
    const auto ps = atom::single_scattering(tf, p.g, p.bins);
    const double n = p.photons_per_row, unscattered = std::exp(-2 * tf);
    std::vector<double> obs, expect;
    double p_single = 0;
    for (uint32_t b = 0; b < p.bins; ++b) {
      obs.push_back(t.h(0, b) - (b == p.bins - 1 ? t.h(0, p.bins + kScatterUnscattered) : 0));
      expect.push_back(n * ps[b]);
      p_single += ps[b];
    }
    obs.push_back(t.h(0, p.bins + kScatterUnscattered));
    expect.push_back(n * unscattered);
    obs.push_back(t.h(0, p.bins + kScatterCapped));
    expect.push_back(n * (1 - unscattered - p_single));
    int dof;
    const double chi = chi_square(obs, expect, dof);
    CAPTURE(dof);
    CHECK(chi < chi_critical(dof));
    // Each once-scattered photon carries the albedo.
    double w = 0, h = 0;
    for (uint32_t b = 0; b + 1 < p.bins; ++b) w += t.w(0, b), h += t.h(0, b);
    CHECK(w == doctest::Approx(p.albedo * h / n).epsilon(1e-5));
  }
  // Full multiple scattering at small tau: the scattered weight is the single-scattering weight
  // up to O(tau^2) (second-order scattering) and the sampling noise.
  ScatterTableParams p;
  p.rows = 1;
  p.first_row = 1;
  p.tau_step = 0.02f;
  p.photons_per_row = 1u << 16;
  const Table t = run_table(test::backend(), p);
  const double tau = double(p.tau_step);
  const auto ps = atom::single_scattering(tau, p.g, p.bins);
  double w = -t.w(0, p.bins + kScatterUnscattered), w1 = 0;
  for (uint32_t b = 0; b < p.bins; ++b) w += t.w(0, b), w1 += p.albedo * ps[b];
  const double sigma = p.albedo * std::sqrt(w1 / p.albedo / p.photons_per_row);
  CHECK(std::abs(w - w1) <= 5 * sigma + 2 * tau * tau);
}

TEST_CASE("scatter_table: rows are reproducible alone and match the CPU reference (chi-square)") {
  ScatterTableParams p;
  p.rows = 12;
  p.tau_step = 0.25f;
  p.photons_per_row = 4096;
  p.direction = {0.48f, -0.6f, 0.64f};
  const Table got = run_table(test::backend(), p);
  const Table want = run_table(test::reference(), p);
  // The same photons on every backend (counter-based RNG): only float rounding lets a few
  // paths part, so the two tables agree far better than two independent samples would.
  for (uint32_t r = 0; r < p.rows; ++r) {
    CAPTURE(r);
    double chi = 0, l1 = 0;
    int dof = -1;
    for (uint32_t e = 0; e < p.bins + kScatterUnscattered; ++e) {
      const double a = got.h(r, e), b = want.h(r, e);
      if (a + b > 0) chi += (a - b) * (a - b) / (a + b), ++dof;
      l1 += std::abs(a - b);
    }
    CHECK(chi < chi_critical(std::max(dof, 1)));
    CHECK(l1 <= 0.05 * 2 * p.photons_per_row);
    CHECK(got.h(r, p.bins + kScatterUnscattered) == want.h(r, p.bins + kScatterUnscattered));
  }
  ScatterTableParams part = p;
  part.first_row = 5;
  part.rows = 2;
  const Table sub = run_table(test::backend(), part);
  for (uint32_t r = 0; r < 2; ++r)
    for (uint32_t e = 0; e < p.bins + kScatterExtras; ++e) CHECK(sub.h(r, e) == got.h(r + 5, e));
}

TEST_CASE("scatter_table rejects bad input, naming the field") {
  Backend& b = test::backend();
  auto table = b.create<Real>(75, "table");
  auto hits = b.create<uint32_t>(75, "hits");
  ScatterTableParams p;
  p.rows = 1;
  p.bins = 1;
  CHECK_THROWS_WITH_AS(b.scatter_table(p, table, hits), doctest::Contains("invalid bins = 1"),
                       Error);
  p.bins = 72;
  p.direction = {1, 1, 0};
  CHECK_THROWS_WITH_AS(b.scatter_table(p, table, hits), doctest::Contains("direction"), Error);
  p.direction = {0, 0, 1};
  p.max_scatterings = 6000;
  CHECK_THROWS_WITH_AS(b.scatter_table(p, table, hits), doctest::Contains("max_scatterings"),
                       Error);
  p.max_scatterings = 10;
  p.weight_threshold = 1;
  CHECK_THROWS_WITH_AS(b.scatter_table(p, table, hits), doctest::Contains("weight_threshold"),
                       Error);
  p.weight_threshold = 0.1f;
  p.rows = 2;
  CHECK_THROWS_WITH_AS(b.scatter_table(p, table, hits), doctest::Contains("table size"), Error);
  p.rows = 1;
  p.albedo = 1.5f;
  CHECK_THROWS_WITH_AS(b.scatter_table(p, table, hits), doctest::Contains("albedo"), Error);
}

TEST_CASE("scatter tables are cached on disk, keyed by every parameter") {
  // Unique per process: the Vulkan variants of this binary may run at the same time.
  const std::string dir =
      (std::filesystem::temp_directory_path() /
       ("masav_scatter_cache_" + test::backend_name() + "_" + std::to_string(::getpid())))
          .string();
  ScatterTableParams p;
  p.rows = 3;
  p.photons_per_row = 256;
  std::filesystem::remove_all(dir);
  bool hit = true;
  const auto first = atom::scatter_table_cached(test::backend(), p, dir, &hit);
  CHECK_FALSE(hit);
  const auto again = atom::scatter_table_cached(test::backend(), p, dir, &hit);
  CHECK(hit);
  CHECK(again.hits == first.hits);
  CHECK(again.weight == first.weight);
  ScatterTableParams other = p;
  other.g = 0.5f;  // any parameter changes the key
  CHECK(atom::scatter_cache_path(other, dir) != atom::scatter_cache_path(p, dir));
  atom::scatter_table_cached(test::backend(), other, dir, &hit);
  CHECK_FALSE(hit);
  {  // a damaged file is ignored and rewritten
    std::ofstream(atom::scatter_cache_path(p, dir), std::ios::trunc) << "junk";
  }
  atom::scatter_table_cached(test::backend(), p, dir, &hit);
  CHECK_FALSE(hit);
  CHECK(atom::load_scatter_cache(p, dir).has_value());
  {  // damage the issue found used as is: each is detected, recomputed, equal to a fresh table
    const std::string path = atom::scatter_cache_path(p, dir);
    const auto read = [&] {
      std::ifstream in(path, std::ios::binary);
      return std::string(std::istreambuf_iterator<char>(in), {});
    };
    const auto write = [&](const std::string& bytes) {
      std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
    };
    const std::string good = read();
    const size_t payload_at = good.size() - first.weight.size() * 12;  // weights, then hits
    const auto recomputed_on = [&](const std::string& bytes) {
      write(bytes);
      CHECK_FALSE(atom::load_scatter_cache(p, dir).has_value());
      bool h = true;
      const auto t = atom::scatter_table_cached(test::backend(), p, dir, &h);
      CHECK_FALSE(h);
      CHECK(t.weight == first.weight);
      CHECK(t.hits == first.hits);
      CHECK(read() == good);  // rewritten whole
    };
    std::string nans = good;  // the payload overwritten at the same size: NaN light before
    const double nan = std::nan("");
    for (size_t i = 0; i < first.weight.size(); ++i)
      std::memcpy(&nans[payload_at + 8 * i], &nan, 8);
    recomputed_on(nans);
    for (size_t at : {payload_at + 3, payload_at + first.weight.size() * 8 + 1, size_t(20)}) {
      std::string flipped = good;  // one bit in a weight, in a hit count, in the header
      flipped[at] = char(flipped[at] ^ 0x04);
      recomputed_on(flipped);
    }
    recomputed_on(good.substr(0, good.size() - 4));  // truncated
    // Another key's file under this name (a hash collision or a copied file).
    atom::scatter_table_cached(test::backend(), other, dir, &hit);
    std::ifstream o(atom::scatter_cache_path(other, dir), std::ios::binary);
    recomputed_on(std::string(std::istreambuf_iterator<char>(o), {}));
    // A checksum that matches values no computation gives: the values are checked too.
    std::string payload = good.substr(good.find('\n', good.find("\npayload ") + 1) + 1);
    const double two = 2.0;  // a weight is a fraction of the photons' weight: at most 1
    std::memcpy(&payload[payload.find('\n') + 1], &two, 8);
    const std::string forged = dir + "/forged.bin";
    write_cache_file(forged, {"scatter-table", 2, atom::scatter_cache_key(p)}, payload);
    // The envelope is intact: only the values can reject it.
    CHECK(read_cache_file(forged, {"scatter-table", 2, atom::scatter_cache_key(p)}, payload.size())
              .payload == payload);
    std::ifstream fin(forged, std::ios::binary);
    recomputed_on(std::string(std::istreambuf_iterator<char>(fin), {}));
  }
  // The phase table drops the unscattered photons from the forward bin.
  const auto phase = atom::make_phase_table(first);
  const uint32_t s = p.bins + kScatterExtras;
  CHECK(phase[0 * p.bins + p.bins - 1] == doctest::Approx(0.0));
  CHECK(phase[2 * p.bins + 10] == first.weight[2 * s + 10]);
  std::filesystem::remove_all(dir);
}

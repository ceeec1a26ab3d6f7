#pragma once
// Shared pieces of the electron-cloud benchmarks: the thesis's Table 2.3 (states, particle
// counts, and its Quadro FX 5800 / Core2 Duo P8400 times) and small helpers.
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "app/bench_common.h"
#include "app/host_environment.h"
#include "app/progress.h"
#include "engine/atom/atom_scene.h"
#include "engine/atom/orbital.h"

namespace masav::app {

struct ThesisRow {
  const char* state;
  uint32_t particles;
  double creation_s;   // "Electron Cloud Creation (sec)", CPU
  double color_cpu_s;  // "Color CPU (sec)"
  double color_gpu_s;  // "Color GPU (sec)"
};

// Thesis Table 2.3.
inline constexpr std::array<ThesisRow, 10> kThesisTable23 = {{
    {"state1", 630720, 4.1, 44.7, 0.288},
    {"state2", 483552, 3.6, 35.5, 0.227},
    {"state3", 316512, 3.2, 26.4, 0.164},
    {"state4", 1124640, 9.8, 67.4, 0.516},
    {"state5", 452016, 3.8, 34.3, 0.211},
    {"state6", 318528, 3.2, 24.8, 0.161},
    {"state7", 1123632, 10.3, 67.1, 0.499},
    {"state8", 165312, 1.9, 29.3, 0.126},
    {"state9", 132192, 1.5, 27.5, 0.105},
    {"state10", 1000001, 8.7, 64.1, 0.197},
}};

// The options of the Table 2.3 benchmarks (atom, light): the fraction of the thesis's particle
// counts to run, and the timed runs of each row.
struct Table23Options : BenchOptions {
  double scale = 1.0;
  int reps = 3;
};
inline void add_table23_options(CLI::App& cmd, Table23Options& o) {
  add_ranged_option(cmd, "--scale", o.scale, "fraction of the thesis's particle counts", 1e-4,
                    16.0);
  add_reps_option(cmd, o.reps);
}

// `row` for each backend and each state of Table 2.3 with its particle count times `scale` (at
// least 1), every one under run_row with the backend and the state as its label; 1 if one
// failed, else 0.
inline int for_each_thesis_row(
    const std::vector<std::unique_ptr<Backend>>& backends, double scale,
    const std::function<void(Backend&, const ThesisRow&, uint32_t particles)>& row) {
  int rc = 0;
  Progress progress("rows of Table 2.3", backends.size() * kThesisTable23.size());
  for (const auto& b : backends)
    for (const ThesisRow& r : kThesisTable23) {
      const uint32_t particles = std::max(1u, uint32_t(std::lround(r.particles * scale)));
      const std::string label = fmt::format("{:<8} {:<8}", b->name(), r.state);
      if (!run_row(label, [&] { row(*b, r, particles); })) rc = 1;
      progress.advance(fmt::format("{} {} particles", label, particles));
    }
  progress.finish();
  return rc;
}

// The electron-cloud scene of a benchmark: a preset state, its particle count and the photons per
// tau row of the scattering table (which only feeds the lookups there).
inline atom::AtomSceneOptions bench_scene_options(const char* state, uint32_t particles,
                                                  uint32_t photons) {
  atom::AtomSceneOptions so;
  so.cache_dir = host_environment().cache_dir().string();  // the table as `masav atom` keeps it
  so.state = atom::preset_state(state);
  so.particles = particles;
  so.scatter.photons_per_row = photons;
  return so;
}

// Thesis §3.4: raymarching the 60^3 volume took 32-37 ms per frame on the Quadro FX 5800.
inline constexpr double kThesisRaymarchMs[2] = {32.0, 37.0};

}  // namespace masav::app

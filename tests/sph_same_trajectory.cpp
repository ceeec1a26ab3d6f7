// sph_same_trajectory A B: whether the SPH checkpoints A and B hold the same trajectory, bit
// for bit: the scene, the time stepping, the block schedule, the watchdog and the particles.
// Fields derived from the state (density, pressure, and accelerations other than leapfrog's
// carried force) are left out with their validity flags: a state read recomputes them without
// touching the trajectory. Prints the first field that differs; exit 1 then, 2 on a bad file.
#include <cstdio>
#include <cstring>
#include <exception>
#include <string>
#include <vector>

#include "engine/sph/sph_checkpoint.h"

using namespace masav;

namespace {

template <class T>
bool same_bits(const T& a, const T& b) {
  return std::memcmp(&a, &b, sizeof(T)) == 0;
}

template <class T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

bool same_stats(const SphStepStats& a, const SphStepStats& b) {
  return same_bits(a.max_speed, b.max_speed) && same_bits(a.max_accel, b.max_accel) &&
         same_bits(a.max_drift, b.max_drift) && same_bits(a.max_density, b.max_density) &&
         a.max_candidates == b.max_candidates && a.max_neighbors == b.max_neighbors &&
         a.outside == b.outside;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: sph_same_trajectory A B (two checkpoint.masav files)\n");
    return 2;
  }
  SphCheckpoint a, b;
  try {
    a = read_sph_checkpoint(argv[1]);
    b = read_sph_checkpoint(argv[2]);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  }
  const SphResumeState &x = a.state, &y = b.state;
  const bool carried = a.scene.integrator == SphIntegrator::leapfrog;
  const std::string scene = sph_scene_difference(a.scene, b.scene);
  const char* differs =
      !scene.empty()                                               ? scene.c_str()
      : !same_bits(x.time, y.time)                                 ? "time"
      : !same_bits(x.last_dt, y.last_dt)                           ? "last_dt"
      : !same_bits(x.adaptive_dt, y.adaptive_dt)                   ? "adaptive_dt"
      : x.steps != y.steps                                         ? "steps"
      : x.substeps != y.substeps                                   ? "substeps"
      : x.retries != y.retries                                     ? "retries"
      : x.block_replays != y.block_replays                         ? "block_replays"
      : !same_stats(x.stats, y.stats)                              ? "stats"
      : !same_stats(x.lag_stats, y.lag_stats)                      ? "lag_stats"
      : x.block_steps != y.block_steps                             ? "block_steps"
      : !same_bits(x.block_limit, y.block_limit)                   ? "block_limit"
      : x.block_stats != y.block_stats                             ? "block_stats"
      : !same_bits(x.watchdog.max_speed, y.watchdog.max_speed)     ? "watchdog.max_speed"
      : !same_bits(x.watchdog.max_density, y.watchdog.max_density) ? "watchdog.max_density"
      : !same_bits(x.watchdog.energy0, y.watchdog.energy0)         ? "watchdog.energy0"
      : x.next_energy_check != y.next_energy_check                 ? "next_energy_check"
      : !same_bits(x.positions, y.positions)                       ? "positions"
      : !same_bits(x.velocities, y.velocities)                     ? "velocities"
      : x.ids != y.ids                                             ? "ids"
      : carried && x.accel_valid != y.accel_valid                  ? "accel_valid"
      : carried && x.accel_valid && !same_bits(x.accel, y.accel)   ? "accel"
      : x.solve_stats.density_iterations != y.solve_stats.density_iterations
          ? "solve_stats.density_iterations"
      : x.solve_stats.divergence_iterations != y.solve_stats.divergence_iterations
          ? "solve_stats.divergence_iterations"
      : !same_bits(x.kappa_density, y.kappa_density)       ? "kappa_density"
      : !same_bits(x.kappa_divergence, y.kappa_divergence) ? "kappa_divergence"
      : !same_bits(x.good_time, y.good_time)               ? "good_time"
      : x.good_steps != y.good_steps                       ? "good_steps"
      : !same_bits(x.good_positions, y.good_positions)     ? "good_positions"
      : !same_bits(x.good_velocities, y.good_velocities)   ? "good_velocities"
                                                           : nullptr;
  if (differs) {
    std::printf("%s differs\n", differs);
    return 1;
  }
  return 0;
}

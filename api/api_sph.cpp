#include <cmath>

#include <fmt/format.h>

#include "engine/core/error.h"
#include "engine/io/writable_paths.h"
#include "engine/sph/sph_checkpoint.h"
#include "engine/sph/sph_export.h"
#include "masav/sph.h"

namespace masav {

std::unique_ptr<SphSimulation> make_sph(Backend& backend, const SphSceneOptions& options) {
  return std::make_unique<SphSimulation>(backend, make_sph_scene(options, "masav::make_sph"));
}

std::unique_ptr<SphSimulation> restore_sph(Backend& backend, const std::string& checkpoint_dir) {
  if (checkpoint_dir.empty())
    throw_invalid("masav::restore_sph", "checkpoint_dir", "''", "a checkpoint directory");
  const std::string path = SphRun::checkpoint_path(checkpoint_dir);
  const SphCheckpoint c = read_sph_checkpoint(path);
  auto sim = std::make_unique<SphSimulation>(backend, c.scene);
  restore_sph_checkpoint(*sim, c, path);
  return sim;
}

void save_sph_checkpoint(SphSimulation& sim, const std::string& checkpoint_dir) {
  if (checkpoint_dir.empty())
    throw_invalid("masav::save_sph_checkpoint", "checkpoint_dir", "''", "a directory");
  ensure_writable_dir(checkpoint_dir, "checkpoint_dir");
  write_sph_checkpoint(SphRun::checkpoint_path(checkpoint_dir), sim);
}

uint64_t run_sph_to(SphSimulation& sim, double t_end) {
  if (!std::isfinite(t_end) || !(t_end > sim.time()))
    throw_invalid("masav::run_sph_to", "t_end", fmt::format("{}", t_end),
                  fmt::format("a finite time after the simulation's t = {} s", sim.time()));
  uint64_t steps = 0;
  // run() stops at t_end; a step cap keeps a dt that shrank to nothing from looping forever
  // (the watchdog and the CFL guard end such a run long before).
  while (sim.time() < t_end) {
    const uint64_t taken = sim.run(1u << 20, t_end);
    steps += taken;
    if (taken == 0) break;
  }
  return steps;
}

void save_sph_vtp(SphSimulation& sim, const std::string& path) {
  write_sph_vtp(path, sim.download());
}

}  // namespace masav

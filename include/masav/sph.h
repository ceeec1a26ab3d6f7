#pragma once
/// \file
/// SPH fluids. `SphSimulation` (engine/sph/sph_simulation.h) is one scene's particles on one
/// backend: `step()`, `run(steps, t_end)`, `time()`, `download()` (positions, velocities,
/// density and pressure in particle-id order) and the device buffers without a copy. `SphRun`
/// (engine/sph/sph_run.h) runs it with the outputs of `masav sph`: the per-step CSV, .vtp
/// snapshots and checkpoints. Scenes come from `SphSceneOptions` (a preset and overrides, as
/// `masav sph` takes them).
#include <memory>
#include <string>

#include "engine/sph/sph_run.h"
#include "engine/sph/sph_scene_options.h"
#include "engine/sph/sph_simulation.h"

namespace masav {

/// A simulation of the scene `options` builds, on `backend` (which must outlive it). Throws
/// masav::Error naming the option out of range or in conflict with the pressure model.
std::unique_ptr<SphSimulation> make_sph(Backend& backend, const SphSceneOptions& options = {});

/// The simulation a checkpoint directory holds (written by save_sph_checkpoint(), `masav sph
/// --checkpoint-dir` or SphRun), restored on `backend` to continue bit for bit.
std::unique_ptr<SphSimulation> restore_sph(Backend& backend, const std::string& checkpoint_dir);

/// Writes the state of `sim` to DIR/checkpoint.masav (atomically replaced).
void save_sph_checkpoint(SphSimulation& sim, const std::string& checkpoint_dir);

/// Runs `sim` to `t_end` seconds of simulated time (from its current time), without outputs.
/// Returns the steps taken; throws masav::Error when the simulation fails (the state is then
/// the last good step's).
uint64_t run_sph_to(SphSimulation& sim, double t_end);

/// Writes the current state as a VTK PolyData file (.vtp: positions, velocity, density,
/// pressure and id per particle) for ParaView.
void save_sph_vtp(SphSimulation& sim, const std::string& path);

}  // namespace masav

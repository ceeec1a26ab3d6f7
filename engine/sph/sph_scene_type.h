#pragma once
// The `sph` scene type: the SPH fluid of issue 3 on screen. SphSimulation (the driver every SPH
// tool uses) is stepped by the frame clock, `sph.substeps` steps per rendered frame; the
// particles are drawn straight from its buffers (bound without a copy when the backend is
// Vulkan), coloured by speed, density or pressure, obstacle particles in grey, inside the box.
//
// Stages (inputs in brackets):
//   simulation  builds the particles, the grid and the first force pass
//               [every sph.* key but color_by and substeps: such a change restarts]
//   step        sph.substeps simulation steps  [simulation, frame]
// "frame" is touched when the clock's frame advances and the clock is not paused (or on
// step_once). Colour-by, camera and render changes touch neither input: nothing reruns, the
// renderer just draws the same buffers differently (the stage counters prove it).
#include "engine/scene/scene.h"

namespace masav {
class SphSimulation;
}

namespace masav::sph {

scene::SceneType sph_scene_type();
// The driver of an sph scene instance (null before its first update or for another type).
const SphSimulation* simulation_of(const scene::SceneInstance& s);

}  // namespace masav::sph

#pragma once
// The SPH scene's shortcuts in the demo panel, beyond the widgets its schema gives: one button
// per preset (each restarts the simulation), the integrator as radio buttons, the simulated time
// per second (asked for and achieved), and what the simulation is doing (simulated time, steps,
// dt, CFL limit, particles).
#include "app/demo/demo_panel.h"

namespace masav::app {

void sph_controls(render::ScenePlayer& player, DemoState& st);

}  // namespace masav::app

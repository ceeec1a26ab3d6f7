#pragma once
// The demo's shortcuts for the atom and atom-volume scenes (SPEC §3): the thesis's ten states
// as buttons, and the source power's three thesis settings beside the schema's 25K-step slider.
#include "app/demo/demo_panel.h"

namespace masav::app {

// Draws the controls when the scene has an [atom] table; nothing otherwise.
void atom_controls(render::ScenePlayer& player, DemoState& st);

}  // namespace masav::app

#pragma once
// The demo's transfer function editor (atom-volume and volume scenes): the control points over a
// log-scaled histogram of the volume's normalised values (click on empty space: add a point;
// drag: move it, left-right its value, up-down its opacity; right click: delete it), the selected
// point's colour and opacity, a strip of the resampled function, "Save TF..." and "Load TF..." in
// the `--tf` file format, and a reset to the default. Every edit goes to the scene's inline key
// (tf_points.h), so only the transfer function's stages and the raymarch rerun.
#include "app/demo/demo_panel.h"

namespace masav::app {

// Draws the editor when the scene has a transfer function; nothing otherwise.
void tf_editor(render::ScenePlayer& player, DemoState& st);

}  // namespace masav::app

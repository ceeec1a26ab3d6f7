#pragma once
// Where the demo draws what: the scene in its own viewport at the window's left, the panel (or,
// collapsed, a narrow strip with the button that expands it) at its right, never overlapping.
#include <cstdint>

namespace masav::app {

struct DemoLayout {
  uint32_t window_w = 0, window_h = 0;  // the frame: the window's framebuffer
  uint32_t scene_w = 0, scene_h = 0;    // the scene's viewport, at the top left
  uint32_t panel_x = 0, panel_w = 0;    // the panel or its strip, full height, right of the scene
  bool expanded = true;
};

// The panel is wide enough for its labels at the UI scale, at most 45% of the window (but never
// narrower than 300 px); collapsed it is a strip of 32 px (scaled). The scene gets the rest, at
// least 16 px (the smallest render.width).
DemoLayout make_layout(uint32_t window_w, uint32_t window_h, bool expanded, float ui_scale);

// The demo's window in a work area: 90% of it, at least 960x600 (the panel and a useful scene
// beside it) unless the work area itself is smaller; 960x600 when no monitor reports one.
void fit_window(uint32_t work_w, uint32_t work_h, uint32_t& width, uint32_t& height);

}  // namespace masav::app

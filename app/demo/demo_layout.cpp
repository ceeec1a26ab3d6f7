#include "app/demo/demo_layout.h"

#include <algorithm>

namespace masav::app {

DemoLayout make_layout(uint32_t window_w, uint32_t window_h, bool expanded, float ui_scale) {
  DemoLayout l;
  l.window_w = window_w;
  l.window_h = window_h;
  l.expanded = expanded;
  const float scale = std::max(1.0f, ui_scale);
  const float wide = std::min(420.0f * scale, std::max(300.0f, 0.45f * float(window_w)));
  const uint32_t want = uint32_t(expanded ? wide : 32.0f * scale);
  l.panel_w = std::min(want, window_w > 16 ? window_w - 16 : 0u);
  // render.width and height allow 16 to 8192 px.
  l.scene_w = std::clamp(window_w - l.panel_w, 16u, 8192u);
  l.scene_h = std::clamp(window_h, 16u, 8192u);
  l.panel_x = l.scene_w;
  return l;
}

void fit_window(uint32_t work_w, uint32_t work_h, uint32_t& width, uint32_t& height) {
  constexpr uint32_t kMinW = 960, kMinH = 600;
  if (work_w == 0 || work_h == 0) {  // no monitor reported: the minimum
    width = kMinW, height = kMinH;
    return;
  }
  width = std::min(work_w, std::max(kMinW, work_w * 9 / 10));
  height = std::min(work_h, std::max(kMinH, work_h * 9 / 10));
}

}  // namespace masav::app

#pragma once
// How long the pointer must rest on a panel control before its tooltip shows, so tooltips do not
// flash while the pointer moves across the panel. The packaged Dear ImGui (1.86) has no hover
// delay of its own (ImGuiHoveredFlags_DelayNormal came in 1.88), so the demo keeps the timer.
#include <cstdint>

namespace masav::app {

constexpr double kTooltipDelayS = 0.5;

// The timer, without ImGui: which control the pointer is on and since when it rested there.
class HoverDelay {
 public:
  // Called each frame in which a control is hovered: `item` names it, `moved` says the pointer
  // moved this frame, `frame` counts frames (a frame without a call ends the hover). True once
  // the pointer has rested on the same control for kTooltipDelayS; moving within it after that
  // keeps the tooltip.
  bool due(uint64_t item, bool moved, double now_s, int frame);

 private:
  uint64_t item_ = 0;
  int last_frame_ = -2;
  double rest_since_s_ = 0;
  bool shown_ = false;
};

}  // namespace masav::app

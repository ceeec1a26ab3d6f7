#include "app/demo/hover_delay.h"

namespace masav::app {

bool HoverDelay::due(uint64_t item, bool moved, double now_s, int frame) {
  const bool same = item == item_ && frame <= last_frame_ + 1;
  last_frame_ = frame;
  if (!same) {
    item_ = item;
    shown_ = false;
    rest_since_s_ = now_s;
  } else if (moved && !shown_) {
    rest_since_s_ = now_s;
  }
  if (now_s - rest_since_s_ >= kTooltipDelayS) shown_ = true;
  return shown_;
}

}  // namespace masav::app

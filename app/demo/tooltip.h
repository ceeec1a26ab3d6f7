#pragma once
// Panel tooltips after the pointer rests on a control (hover_delay.h):
//   if (tooltip_due()) ImGui::SetTooltip("...");
#include "app/demo/hover_delay.h"

namespace masav::app {

// For the item just drawn: hovered, and the pointer has rested on it for kTooltipDelayS.
bool tooltip_due();

}  // namespace masav::app

#include "app/demo/tooltip.h"

#include <imgui.h>

#include <functional>

namespace masav::app {

bool tooltip_due() {
  static HoverDelay delay;
  if (!ImGui::IsItemHovered()) return false;
  // The item's rectangle names it: controls do not move while the pointer rests on one.
  const ImVec2 lo = ImGui::GetItemRectMin(), hi = ImGui::GetItemRectMax();
  const std::hash<float> h;
  const uint64_t item = h(lo.x) ^ (h(lo.y) << 1) ^ (h(hi.x) << 2) ^ (h(hi.y) << 3);
  const ImGuiIO& io = ImGui::GetIO();
  return delay.due(item, io.MouseDelta.x != 0 || io.MouseDelta.y != 0, ImGui::GetTime(),
                   ImGui::GetFrameCount());
}

}  // namespace masav::app

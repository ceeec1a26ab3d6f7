#include "render/overlay.h"

#include <fmt/format.h>
#include <imgui.h>

namespace masav::render {

std::string clock_line(uint64_t frame, double clock_s, std::optional<double> simulated_s) {
  if (simulated_s)
    return fmt::format("frame {}  t = {:.4f} s simulated (frame clock {:.2f} s)", frame,
                       *simulated_s, clock_s);
  return fmt::format("frame {}  t = {:.2f} s", frame, clock_s);
}

std::vector<std::string> overlay_lines(const OverlayInfo& info) {
  std::vector<std::string> lines;
  lines.push_back(info.title.empty() ? "masav" : info.title);
  lines.push_back(
      clock_line(info.frame, info.time_s, info.simulated_time_s) +
      (info.fps > 0 ? fmt::format("  {:.1f} fps ({:.1f} ms)", info.fps, info.frame_ms) : ""));
  if (!info.progress.empty()) lines.push_back(info.progress);
  lines.push_back(fmt::format("compute: {} ({})", info.backend, info.device));
  lines.push_back(info.render_device.empty()
                      ? "render: same device, no copies"
                      : fmt::format("render: {} (copies)", info.render_device));
  if (!info.verify.empty()) lines.push_back(info.verify);
  if (!info.legend.empty()) lines.push_back(info.legend);
  for (const auto& s : info.stages)
    if (s.created)
      lines.push_back(fmt::format("  {:<20} {:>8.3f} ms  ran {}x", s.name, s.last_ms, s.runs));
  return lines;
}

void draw_overlay(const OverlayInfo& info) {
  const std::vector<std::string> lines = overlay_lines(info);
  ImDrawList* dl = ImGui::GetForegroundDrawList();
  const float scale = ImGui::GetIO().FontGlobalScale;
  const float line_h = ImGui::GetFontSize() + 2.0f * scale;
  float width = 0;
  for (const auto& l : lines) width = std::max(width, ImGui::CalcTextSize(l.c_str()).x);
  const ImVec2 origin(8.0f * scale, 8.0f * scale);
  const float pad = 5.0f * scale;
  dl->AddRectFilled(ImVec2(origin.x - pad, origin.y - pad),
                    ImVec2(origin.x + width + pad, origin.y + line_h * float(lines.size()) + pad),
                    IM_COL32(0, 0, 0, 150), 4.0f * scale);
  for (size_t i = 0; i < lines.size(); ++i)
    dl->AddText(ImVec2(origin.x, origin.y + line_h * float(i)),
                i == 0 ? IM_COL32(255, 220, 120, 255) : IM_COL32(235, 235, 235, 255),
                lines[i].c_str());
  if (info.colour_bar) draw_colour_bar(*info.colour_bar);
}

}  // namespace masav::render

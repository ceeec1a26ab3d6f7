#include "render/colour_bar.h"

#include <fmt/format.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>

namespace masav::render {

std::vector<double> nice_ticks(double lo, double hi, int target) {
  if (!(hi > lo) || !std::isfinite(lo) || !std::isfinite(hi)) return {lo};
  const double raw = (hi - lo) / double(std::max(target, 1));
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  double step = 10.0 * mag;
  for (double f : {1.0, 2.0, 5.0})
    if (f * mag >= raw) {
      step = f * mag;
      break;
    }
  std::vector<double> t;
  const double eps = 1e-9 * (hi - lo);
  for (double k = std::ceil((lo - eps) / step); k * step <= hi + eps; k += 1.0) {
    const double v = k * step;
    t.push_back(std::abs(v) < eps ? 0.0 : v);
  }
  return t;
}

std::string tick_label(double value, double step) {
  const double a = std::max(std::abs(value), step);
  if (a >= 1e5 || (step > 0 && step < 1e-3)) return fmt::format("{:.2g}", value);
  const int decimals = step > 0 ? std::max(0, int(-std::floor(std::log10(step) + 1e-9))) : 0;
  return fmt::format("{:.{}f}", value, decimals);
}

ColourBarLayout colour_bar_layout(const ColourBar& bar, float height, float scale,
                                  float line_height) {
  ColourBarLayout l;
  const std::vector<double> values = nice_ticks(bar.lo, bar.hi);
  const double step = values.size() > 1 ? values[1] - values[0] : 0.0;
  for (double v : values) l.ticks.push_back({v, tick_label(v, step), 0});
  // Bottom left: the overlay's text is at the top left, the demo's panel at the right.
  const float margin = 12.0f * scale, gap = 6.0f * scale, bar_w = 14.0f * scale;
  l.x0 = margin;
  l.x1 = l.x0 + bar_w;
  l.y1 = height - margin - 0.5f * line_height;
  l.y0 = l.y1 - std::max(40.0f * scale, 0.3f * height);
  l.title_x = margin;
  l.title_y = l.y0 - gap - line_height;
  const double span = double(bar.hi) - double(bar.lo);
  for (ColourBarTick& t : l.ticks)
    t.y = span > 0 ? l.y1 - float((t.value - bar.lo) / span) * (l.y1 - l.y0) : 0.5f * (l.y0 + l.y1);
  return l;
}

Vec4f colour_at(const ColourBar& bar, double value) {
  if (bar.colours.empty()) return {1, 1, 1, 1};
  const double span = double(bar.hi) - double(bar.lo);
  const double t = span > 0 ? std::clamp((value - bar.lo) / span, 0.0, 1.0) : 0.5;
  const double x = t * double(bar.colours.size() - 1);
  const size_t k = std::min(size_t(x), bar.colours.size() - 1);
  const size_t k1 = std::min(k + 1, bar.colours.size() - 1);
  const float f = float(x - double(k));
  const Vec4f& a = bar.colours[k];
  const Vec4f& b = bar.colours[k1];
  return {a.x + (b.x - a.x) * f, a.y + (b.y - a.y) * f, a.z + (b.z - a.z) * f, 1.0f};
}

namespace {

float imgui_text_width(const std::string& s) {
  return ImGui::CalcTextSize(s.c_str()).x;
}

ImU32 to_imgui(const Vec4f& c) {
  return ImGui::ColorConvertFloat4ToU32(ImVec4(c.x, c.y, c.z, 1.0f));
}

}  // namespace

ColourBarLayout colour_bar_layout_in_frame(const ColourBar& bar) {
  const ImGuiIO& io = ImGui::GetIO();
  return colour_bar_layout(bar, io.DisplaySize.y, io.FontGlobalScale, ImGui::GetFontSize());
}

ColourBarLayout draw_colour_bar(const ColourBar& bar) {
  const float scale = ImGui::GetIO().FontGlobalScale;
  const float line_h = ImGui::GetFontSize();
  const ColourBarLayout l = colour_bar_layout_in_frame(bar);
  ImDrawList* dl = ImGui::GetForegroundDrawList();
  const float pad = 5.0f * scale;
  float right = l.x1;
  for (const auto& t : l.ticks)
    right = std::max(right, l.x1 + 6.0f * scale + imgui_text_width(t.label));
  right = std::max(right, l.title_x + imgui_text_width(bar.title));
  dl->AddRectFilled(ImVec2(l.x0 - pad, l.title_y - pad),
                    ImVec2(right + pad, l.y1 + 0.5f * line_h + pad), IM_COL32(0, 0, 0, 150),
                    4.0f * scale);
  dl->AddText(ImVec2(l.title_x, l.title_y), IM_COL32(235, 235, 235, 255), bar.title.c_str());
  // The gradient in slices, each from its bottom colour to its top colour.
  constexpr int kSlices = 64;
  for (int i = 0; i < kSlices; ++i) {
    const float ya = l.y1 - (l.y1 - l.y0) * float(i + 1) / kSlices;
    const float yb = l.y1 - (l.y1 - l.y0) * float(i) / kSlices;
    const double span = double(bar.hi) - double(bar.lo);
    const ImU32 top = to_imgui(colour_at(bar, bar.lo + span * double(i + 1) / kSlices));
    const ImU32 bottom = to_imgui(colour_at(bar, bar.lo + span * double(i) / kSlices));
    dl->AddRectFilledMultiColor(ImVec2(l.x0, ya), ImVec2(l.x1, yb), top, top, bottom, bottom);
  }
  dl->AddRect(ImVec2(l.x0, l.y0), ImVec2(l.x1, l.y1), IM_COL32(200, 200, 200, 255));
  for (const auto& t : l.ticks) {
    dl->AddLine(ImVec2(l.x1, t.y), ImVec2(l.x1 + 4.0f * scale, t.y), IM_COL32(235, 235, 235, 255));
    dl->AddText(ImVec2(l.x1 + 6.0f * scale, t.y - 0.5f * line_h), IM_COL32(235, 235, 235, 255),
                t.label.c_str());
  }
  return l;
}

}  // namespace masav::render

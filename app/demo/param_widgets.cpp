#include "app/demo/param_widgets.h"

#include <fmt/format.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "app/demo/tooltip.h"

namespace masav::app {

bool param_widget(const scene::ParamSpec& spec, const std::string& path,
                  const scene::ParamValue& current, scene::ParamValue& out) {
  using scene::ParamType;
  ImGui::PushID(path.c_str());
  const std::string label =
      spec.unit.empty() ? spec.key : fmt::format("{} ({})", spec.key, spec.unit);
  bool changed = false;
  switch (spec.type) {
    case ParamType::flag: {
      bool v = std::get<bool>(current);
      if (ImGui::Checkbox(label.c_str(), &v)) out = v, changed = true;
      break;
    }
    case ParamType::integer: {
      int64_t v = std::get<int64_t>(current);
      const int64_t lo = spec.int_min, hi = spec.int_max;
      // Wide ranges (counts, seeds) are typed; narrow ones get a slider.
      const bool typed = hi - lo > 100000;
      if (typed) {
        if (ImGui::InputScalar(label.c_str(), ImGuiDataType_S64, &v, nullptr, nullptr, "%lld",
                               ImGuiInputTextFlags_EnterReturnsTrue))
          out = std::clamp(v, lo, hi), changed = true;
      } else if (ImGui::SliderScalar(label.c_str(), ImGuiDataType_S64, &v, &lo, &hi)) {
        out = v, changed = true;
      }
      break;
    }
    case ParamType::real: {
      double v = std::get<double>(current);
      const double lo = spec.real_min, hi = spec.real_max;
      if (spec.step > 0) {
        // A slider that moves in steps (e.g. the source power's >= 10 steps).
        const int steps = int(std::lround((hi - lo) / spec.step));
        int k = int(std::lround((v - lo) / spec.step));
        const std::string shown = fmt::format("{:.6g}", v);
        if (ImGui::SliderInt(label.c_str(), &k, 0, steps, shown.c_str()))
          out = lo + spec.step * k, changed = true;
      } else if (hi - lo > 1e6) {
        if (ImGui::InputDouble(label.c_str(), &v, 0, 0, "%.6g",
                               ImGuiInputTextFlags_EnterReturnsTrue))
          out = std::clamp(v, lo, hi), changed = true;
      } else {
        const ImGuiSliderFlags flags = spec.logarithmic ? ImGuiSliderFlags_Logarithmic : 0;
        if (ImGui::SliderScalar(label.c_str(), ImGuiDataType_Double, &v, &lo, &hi, "%.4g", flags))
          out = v, changed = true;
      }
      break;
    }
    case ParamType::choice: {
      const std::string& v = std::get<std::string>(current);
      if (ImGui::BeginCombo(label.c_str(), v.c_str())) {
        for (const auto& c : spec.choices)
          if (ImGui::Selectable(c.c_str(), c == v) && c != v) out = c, changed = true;
        ImGui::EndCombo();
      }
      break;
    }
    case ParamType::text: {
      char buf[256];
      std::snprintf(buf, sizeof buf, "%s", std::get<std::string>(current).c_str());
      if (ImGui::InputText(label.c_str(), buf, sizeof buf, ImGuiInputTextFlags_EnterReturnsTrue))
        out = std::string(buf), changed = true;
      break;
    }
  }
  if (tooltip_due() && !spec.help.empty())
    ImGui::SetTooltip("%s\n%s", spec.help.c_str(), spec.allowed().c_str());
  ImGui::PopID();
  return changed;
}

}  // namespace masav::app

#include "app/demo/atom_controls.h"

#include <fmt/format.h>
#include <imgui.h>

#include "app/demo/tooltip.h"
#include "engine/atom/orbital.h"

namespace masav::app {

void atom_controls(render::ScenePlayer& player, DemoState& st) {
  const scene::ParamSet& p = player.scene().params();
  if (!p.has_table("atom")) return;
  ImGui::Separator();
  ImGui::TextUnformatted("hydrogen state (thesis Table 2.1)");
  const auto& names = atom::preset_names();
  for (size_t i = 0; i < names.size(); ++i) {
    const atom::OrbitalState s = atom::preset_state(names[i]);
    const std::string label = fmt::format("{}##state", i + 1);
    const bool current = p.get_text("atom.state") == names[i];
    if (current) ImGui::PushStyleColor(ImGuiCol_Button, ImVec4(0.2f, 0.5f, 0.3f, 1));
    if (ImGui::Button(label.c_str(), ImVec2(30, 0))) set_param(player, st, "atom.state", names[i]);
    if (current) ImGui::PopStyleColor();
    if (tooltip_due()) ImGui::SetTooltip("%s: %s", names[i].c_str(), atom::describe(s).c_str());
    if (i % 5 != 4) ImGui::SameLine();
  }
  ImGui::TextDisabled("custom: atom.state = custom, then n, l, m below");
  ImGui::TextUnformatted("source power");
  for (double lm : {50000.0, 250000.0, 500000.0}) {
    const std::string label = fmt::format("{:.0f}K lm", lm / 1000);
    if (ImGui::Button(label.c_str())) set_param(player, st, "nebula.power_lm", lm);
    ImGui::SameLine();
  }
  ImGui::NewLine();
}

}  // namespace masav::app

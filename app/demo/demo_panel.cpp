#include "app/demo/demo_panel.h"

#include <fmt/format.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>

#include "app/demo/atom_controls.h"
#include "app/demo/param_widgets.h"
#include "app/demo/sph_panel.h"
#include "app/demo/tf_editor.h"
#include "app/demo/tooltip.h"
#include "app/demo/volume_open.h"
#include "engine/atom/orbital.h"
#include "engine/core/error.h"
#include "registry/scene_catalog.h"

namespace masav::app {
namespace {

// Controls beyond the schema's, per scene type. The schema already gives every parameter its
// widget; these are the thesis's shortcuts.
// ---- atom and atom-volume (issue 4; the lead fills this in when the scenes are merged):
//      the ten states as preset buttons (state1 ... state10 set atom.n/l/m), the source power
//      slider in >= 10 steps from 50K to 500K lumens (atom.source_power_lm, schema .steps()),
//      the volume mix s/t.
// ---- sph (issue 3): the presets (explosion, water, mud, obstacle), integrator, particle count.
// Scenes that are not built in have no controls here: nothing is shown that would do nothing.
void scene_shortcuts(render::ScenePlayer& player, DemoState& st) {
  atom_controls(player, st);  // atom, atom-volume (app/demo/atom_controls.cpp)
  if (player.file().type == "sph") sph_controls(player, st);
}

// A preset hydrogen state fixes n, l and m: the panel shows the preset's numbers, greyed, rather
// than the custom state's, which the scene does not use then.
std::optional<int64_t> preset_quantum_number(const scene::ParamSet& p, const std::string& path) {
  if (!p.has_table("atom") || p.get_text("atom.state") == "custom") return std::nullopt;
  const atom::OrbitalState s = atom::preset_state(p.get_text("atom.state"));
  if (path == "atom.n") return s.n;
  if (path == "atom.l") return s.l;
  if (path == "atom.m") return s.m;
  return std::nullopt;
}

void table_controls(render::ScenePlayer& player, DemoState& st, const scene::TableSchema& t) {
  for (const scene::ParamSpec& spec : t.params()) {
    const std::string path = t.name() + "." + spec.key;
    // The scene's frame size is its viewport here, which follows the window and the panel.
    if (path == "render.height") continue;
    if (path == "sph.substeps" && st.sim_rate > 0) {  // the rate sets it, frame by frame
      ImGui::TextDisabled("substeps: %lld this frame (from the rate)",
                          (long long)player.scene().params().get_int(path));
      continue;
    }
    if (path == "render.width") {
      ImGui::TextDisabled("width x height: %u x %u px (the scene's viewport)", st.layout.scene_w,
                          st.layout.scene_h);
      continue;
    }
    const std::optional<int64_t> fixed = preset_quantum_number(player.scene().params(), path);
    const scene::ParamValue shown =
        fixed ? scene::ParamValue(*fixed) : player.scene().params().get(path);
    scene::ParamValue next;
    ImGui::BeginDisabled(fixed.has_value());
    if (param_widget(spec, path, shown, next) && !fixed) set_param(player, st, path, next);
    ImGui::EndDisabled();
  }
}

void stage_table(render::ScenePlayer& player) {
  if (!ImGui::BeginTable("stages", 5, ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingFixedFit))
    return;
  for (const char* h : {"stage", "created", "runs", "skipped", "ms"}) ImGui::TableSetupColumn(h);
  ImGui::TableHeadersRow();
  for (const auto& c : player.scene().graph().counters()) {
    ImGui::TableNextRow();
    ImGui::TableNextColumn();
    ImGui::TextUnformatted(c.name.c_str());
    ImGui::TableNextColumn();
    ImGui::TextUnformatted(c.created ? "yes" : "never");
    ImGui::TableNextColumn();
    ImGui::Text("%llu", (unsigned long long)c.runs);
    ImGui::TableNextColumn();
    ImGui::Text("%llu", (unsigned long long)c.skips);
    ImGui::TableNextColumn();
    ImGui::Text("%.3f", c.last_ms);
  }
  ImGui::EndTable();
}

void mouse_camera(render::ScenePlayer& player, DemoState& st) {
  const ImGuiIO& io = ImGui::GetIO();
  if (io.WantCaptureMouse || io.MousePos.x >= float(st.layout.scene_w)) return;
  const scene::ParamSet& p = player.scene().params();
  if (ImGui::IsMouseDragging(ImGuiMouseButton_Left) &&
      (io.MouseDelta.x != 0 || io.MouseDelta.y != 0)) {
    double yaw = p.get_real("camera.yaw_deg") - 0.4 * io.MouseDelta.x;
    yaw = std::remainder(yaw, 360.0);
    const double pitch =
        std::clamp(p.get_real("camera.pitch_deg") + 0.4 * io.MouseDelta.y, -89.0, 89.0);
    set_param(player, st, "camera.view", std::string("orbit"));
    set_param(player, st, "camera.yaw_deg", yaw);
    set_param(player, st, "camera.pitch_deg", pitch);
  }
  if (io.MouseWheel != 0) {
    const double d =
        std::clamp(p.get_real("camera.distance") * std::pow(0.9, io.MouseWheel), 0.1, 100.0);
    set_param(player, st, "camera.distance", d);
  }
}

// The panel's own window: the layout's rectangle, never moved or resized by hand.
bool begin_panel(const char* name, const DemoState& st) {
  ImGui::SetNextWindowPos(ImVec2(float(st.layout.panel_x), 0), ImGuiCond_Always);
  ImGui::SetNextWindowSize(ImVec2(float(st.layout.panel_w), float(st.layout.window_h)),
                           ImGuiCond_Always);
  const ImGuiWindowFlags flags = ImGuiWindowFlags_NoTitleBar | ImGuiWindowFlags_NoMove |
                                 ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse |
                                 ImGuiWindowFlags_NoSavedSettings;
  return ImGui::Begin(name, nullptr, flags);
}

void capture_controls(DemoState& st) {
  if (ImGui::Button("Screenshot")) st.actions.push_back({Action::screenshot});
  ImGui::SameLine();
  if (ImGui::Button(st.recording.empty() ? "Record" : "Stop recording"))
    st.actions.push_back({Action::record});
  ImGui::SameLine();
  if (ImGui::Button("Save scene")) st.actions.push_back({Action::save_scene});
  if (!st.recording.empty())
    ImGui::TextColored(ImVec4(1, 0.5f, 0.4f, 1), "%s", st.recording.c_str());
  if (!st.saved.empty()) ImGui::TextWrapped("%s", st.saved.c_str());
}

void shortcut_table() {
  if (!ImGui::BeginTable("keys", 2, ImGuiTableFlags_SizingFixedFit)) return;
  for (const ShortcutRow& row : shortcut_rows()) {
    ImGui::TableNextRow();
    ImGui::TableNextColumn();
    ImGui::TextUnformatted(row.keys.c_str());
    ImGui::TableNextColumn();
    ImGui::TextUnformatted(row.what.c_str());
  }
  ImGui::EndTable();
}

}  // namespace

void set_param(render::ScenePlayer& player, DemoState& st, const std::string& path,
               const scene::ParamValue& v) {
  try {
    player.scene().set(path, v);
    st.message.clear();
  } catch (const Error& e) {
    st.message = e.what();
  }
}

void draw_panel(render::ScenePlayer& player, DemoState& st) {
  mouse_camera(player, st);
  if (!st.show_panel) {
    begin_panel("##strip", st);
    if (ImGui::Button("<", ImVec2(-1, 0))) st.actions.push_back({Action::panel});
    if (tooltip_due()) ImGui::SetTooltip("expand the panel (Tab)");
    ImGui::End();
    return;
  }
  if (!begin_panel("masav", st)) {
    ImGui::End();
    return;
  }
  // Labels get the right part of the panel, so long ones ("smoothing_radius (m)") fit.
  ImGui::PushItemWidth(ImGui::GetWindowWidth() * 0.45f);
  if (ImGui::Button("> collapse (Tab)")) st.actions.push_back({Action::panel});
  const scene::ParamSet& p = player.scene().params();
  // Scene.
  const std::string current = player.file().source;
  if (ImGui::BeginCombo("scene", std::filesystem::path(current).filename().string().c_str())) {
    for (const auto& f : st.scene_files)
      if (ImGui::Selectable(f.c_str(), f == current) && f != current) st.requests.scene_file = f;
    ImGui::EndCombo();
  }
  ImGui::Text("%s, %.1f fps (%.1f ms)", player.file().type.c_str(), st.fps, st.frame_ms);
  bool open = false;
  volume_open_controls(st.open_fields, open);
  if (open) st.requests.open_volume = st.open_fields;

  // Transport.
  if (ImGui::Button(st.paused ? "Resume" : "Pause")) st.actions.push_back({Action::pause});
  ImGui::SameLine();
  if (ImGui::Button("Step")) st.actions.push_back({Action::step});
  ImGui::SameLine();
  if (ImGui::Button("Reset")) st.actions.push_back({Action::reset});
  capture_controls(st);
  ImGui::TextUnformatted(render::clock_line(player.clock().frame, player.clock().time_s,
                                            player.scene().simulated_time_s())
                             .c_str());
  {
    const scene::ParamSpec& fps = p.spec("run.fps");
    scene::ParamValue next;
    if (param_widget(fps, "run.fps", p.get("run.fps"), next))
      set_param(player, st, "run.fps", next);
    ImGui::SameLine();
    ImGui::TextDisabled("dt %.4g s", 1.0 / p.get_real("run.fps"));
  }

  // Viewpoints.
  for (const char* v : {"front", "top", "left", "orbit"}) {
    if (ImGui::RadioButton(v, p.get_text("camera.view") == v))
      set_param(player, st, "camera.view", std::string(v));
    ImGui::SameLine();
  }
  ImGui::NewLine();
  ImGui::TextDisabled("drag: orbit, wheel: zoom");

  // Backend and the cross-check.
  if (ImGui::BeginCombo("backend", player.backend().name().c_str())) {
    for (const auto& b : st.backends)
      if (ImGui::Selectable(b.c_str(), b == player.backend().name()) &&
          b != player.backend().name())
        st.requests.backend = b;
    ImGui::EndCombo();
  }
  ImGui::TextWrapped("%s", player.backend().caps().device_name.c_str());
  ImGui::TextWrapped("%s", player.verify_status().empty() ? "cross-check: not run"
                                                          : player.verify_status().c_str());
  if (ImGui::Button("Run cross-check")) st.requests.verify = true;

  if (!st.message.empty()) {  // wrapped: a file's refusal names its path and the remedy
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1, 0.4f, 0.3f, 1));
    ImGui::TextWrapped("%s", st.message.c_str());
    ImGui::PopStyleColor();
  }

  // Every parameter of the scene's own tables, then rendering and camera.
  const scene::SceneType& type = scene::find_scene_type(player.file().type);
  scene_shortcuts(player, st);
  tf_editor(player, st);  // atom-volume and volume scenes (app/demo/tf_editor.cpp)
  for (const scene::TableSchema* t : type.tables)
    if (ImGui::CollapsingHeader(t->name().c_str(), ImGuiTreeNodeFlags_DefaultOpen))
      table_controls(player, st, *t);
  for (const char* name : {"render", "camera"})
    if (ImGui::CollapsingHeader(name))
      for (const scene::TableSchema* t : p.tables())
        if (t->name() == name) table_controls(player, st, *t);
  if (ImGui::CollapsingHeader("timings", ImGuiTreeNodeFlags_DefaultOpen)) stage_table(player);
  if (ImGui::CollapsingHeader("keyboard shortcuts", ImGuiTreeNodeFlags_DefaultOpen))
    shortcut_table();
  ImGui::PopItemWidth();
  ImGui::End();
}

}  // namespace masav::app

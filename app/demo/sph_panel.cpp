#include "app/demo/sph_panel.h"

#include <imgui.h>

#include "app/demo/tooltip.h"
#include "engine/sph/sph_scene_schema.h"
#include "engine/sph/sph_scene_type.h"
#include "engine/sph/sph_simulation.h"

namespace masav::app {

void sph_controls(render::ScenePlayer& player, DemoState& st) {
  const scene::ParamSet& p = player.scene().params();
  ImGui::Separator();
  ImGui::TextUnformatted("SPH");
  // Presets (thesis Figures 4.10-4.13, the dam break): a click restarts from its initial state.
  const scene::ParamSpec& preset = p.spec("sph.preset");
  for (size_t i = 0; i < preset.choices.size(); ++i) {
    const std::string& name = preset.choices[i];
    if (i > 0) ImGui::SameLine();
    const bool current = p.get_text("sph.preset") == name;
    if (current) ImGui::BeginDisabled();
    if (ImGui::Button(name.c_str())) set_param(player, st, "sph.preset", name);
    if (current) ImGui::EndDisabled();
  }
  for (const std::string& name : p.spec("sph.integrator").choices) {
    if (ImGui::RadioButton(name.c_str(), p.get_text("sph.integrator") == name))
      set_param(player, st, "sph.integrator", name);
    ImGui::SameLine();
  }
  ImGui::NewLine();
  // Simulated time per wall-clock second: the demo picks the steps per frame to match it.
  bool paced = st.sim_rate > 0;
  if (ImGui::Checkbox("pace", &paced)) st.sim_rate = paced ? 0.1 : 0.0;
  if (tooltip_due()) ImGui::SetTooltip("off: sph.substeps steps per frame");
  ImGui::SameLine();
  float rate = float(st.sim_rate);
  ImGui::BeginDisabled(!paced);
  if (ImGui::SliderFloat("simulated s per s", &rate, 0.001f, 10.0f, "%.3g",
                         ImGuiSliderFlags_Logarithmic))
    st.sim_rate = rate;
  ImGui::EndDisabled();
  ImGui::Text("achieved %.3g s/s (defaults for a %s)", st.sim_rate_achieved,
              st.device_class.c_str());
  // How the particles are drawn: flat sprites, lit spheres, or the fluid's surface.
  for (const std::string& name : p.spec("render.point_style").choices) {
    if (ImGui::RadioButton(name.c_str(), p.get_text("render.point_style") == name))
      set_param(player, st, "render.point_style", name);
    ImGui::SameLine();
  }
  ImGui::NewLine();
  if (const SphSimulation* sim = sph::simulation_of(player.scene())) {
    ImGui::Text("%u particles (%u obstacle), h = %.3g m", sim->particle_count(),
                sim->layout().obstacle, sim->layout().h);
    ImGui::Text("t = %.4f s simulated, %llu steps (%llu retried)", sim->time(),
                (unsigned long long)sim->steps(), (unsigned long long)sim->retries());
    ImGui::Text("dt %.3g s, CFL limit %.3g s, max speed %.3g m/s", sim->last_dt(), sim->dt_limit(),
                sim->last_stats().max_speed);
  }
  ImGui::TextDisabled("every [sph] key but color_by and substeps restarts");
}

}  // namespace masav::app

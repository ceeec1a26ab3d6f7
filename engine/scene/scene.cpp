#include "engine/scene/scene.h"

#include <fmt/format.h>

#include <algorithm>

#include "engine/core/error.h"

namespace masav::scene {

SceneInstance::SceneInstance(Backend& backend, ParamSet params)
    : backend_(backend), params_(std::move(params)) {}

std::string SceneInstance::title() const {
  return params_.get_text("scene.title");
}

void SceneInstance::add_parameter_inputs() {
  for (const TableSchema* t : params_.tables())
    for (const ParamSpec& p : t->params()) graph_.add_input(t->name() + "." + p.key);
  graph_.add_input("view");
  graph_.add_input("preview");
}

void SceneInstance::set_preview_level(uint32_t level) {
  level = std::min(level, max_preview_level());
  if (level == preview_level_) return;
  preview_level_ = level;
  graph_.touch_if_present("preview");
}

bool SceneInstance::view_moves_at(double time_s) const {
  return time_s != view_time_s_ && params_.has("camera.orbit_speed_deg") &&
         params_.get_real("camera.orbit_speed_deg") != 0 && params_.has("camera.view") &&
         params_.get_text("camera.view") == "orbit";
}

bool SceneInstance::changes_pending(const FrameClock& clock) const {
  if (view_moves_at(clock.time_s)) return true;
  for (const std::string& t : targets())
    if (graph_.pending(t, "preview")) return true;
  return false;
}

bool SceneInstance::set(std::string_view path, const ParamValue& v) {
  ParamSet next = params_;
  if (!next.set(path, v)) return false;
  validate(next);
  params_ = std::move(next);
  graph_.touch_if_present(path);
  if (path.rfind("camera.", 0) == 0) graph_.touch_if_present("view");
  return true;
}

bool SceneInstance::set_from_string(std::string_view path, std::string_view text) {
  ParamSet next = params_;
  if (!next.set_from_string(path, text)) return false;
  return set(path, next.get(path));
}

UpdateReport SceneInstance::update(const FrameClock& clock, bool time_stages) {
  if (view_moves_at(clock.time_s)) graph_.touch_if_present("view");
  view_time_s_ = clock.time_s;
  on_clock(clock);
  const std::vector<std::string> t = targets();
  return graph_.update(t, time_stages ? &backend_ : nullptr);
}

}  // namespace masav::scene

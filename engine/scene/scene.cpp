#include "engine/scene/scene.h"

#include <fmt/format.h>

#include "engine/core/error.h"
#include "engine/scene/common_tables.h"

namespace masav::scene {

SceneInstance::SceneInstance(Backend& backend, ParamSet params)
    : backend_(backend), params_(std::move(params)) {}

void SceneInstance::add_parameter_inputs() {
  for (const TableSchema* t : params_.tables())
    for (const ParamSpec& p : t->params()) graph_.add_input(t->name() + "." + p.key);
  graph_.add_input("view");
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
  if (clock.time_s != view_time_s_) {
    if (params_.has("camera.orbit_speed_deg") && params_.get_real("camera.orbit_speed_deg") != 0)
      graph_.touch_if_present("view");
    view_time_s_ = clock.time_s;
  }
  on_clock(clock);
  const std::vector<std::string> t = targets();
  return graph_.update(t, time_stages ? &backend_ : nullptr);
}

std::vector<std::string> scene_type_names() {
  std::vector<std::string> names;
  for (const auto& t : scene_types()) names.push_back(t.name);
  return names;
}

const SceneType& find_scene_type(std::string_view name) {
  for (const auto& t : scene_types())
    if (t.name == name) return t;
  std::string all;
  for (const auto& n : scene_type_names()) all += (all.empty() ? "" : ", ") + n;
  throw_invalid("scene", "scene.type", std::string(name), "one of " + all);
}

ParamSet default_params(const SceneType& type) {
  ParamSet p;
  for (const TableSchema* t : common_tables()) p.add_table(*t);
  for (const TableSchema* t : type.tables) p.add_table(*t);
  p.set("scene.type", type.name);
  return p;
}

}  // namespace masav::scene

#pragma once
// The viewpoint from a scene's [camera] table: the thesis's three fixed views (top, left,
// front) and an orbit camera around the box centre, for a z-up or y-up world. Vulkan clip
// space (y down, depth 0..1).
#include <glm/glm.hpp>

#include "engine/scene/param_schema.h"
#include "engine/scene/scene_view.h"

namespace masav::render {

struct Camera {
  glm::mat4 view{1.0f}, proj{1.0f}, view_proj{1.0f};
  glm::vec3 eye{0.0f}, target{0.0f};
  float distance = 1.0f;  // eye to target: the depth at which point sprites have their size
};

// `time_s` turns an orbit camera by camera.orbit_speed_deg per second.
Camera make_camera(const scene::ParamSet& p, const scene::Box& box, float aspect, double time_s);

}  // namespace masav::render

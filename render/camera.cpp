#include "render/camera.h"

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

namespace masav::render {
namespace {

// The views are defined for a z-up world; a y-up world maps (x, y, z) -> (x, z, -y).
glm::vec3 to_world(glm::vec3 v, bool y_up) {
  return y_up ? glm::vec3(v.x, v.z, -v.y) : v;
}

}  // namespace

Camera make_camera(const scene::ParamSet& p, const scene::Box& box, float aspect, double time_s) {
  const glm::vec3 lo(box.lo.x, box.lo.y, box.lo.z), hi(box.hi.x, box.hi.y, box.hi.z);
  const bool y_up = p.get_text("camera.up") == "y";
  Camera c;
  c.target = 0.5f * (lo + hi);
  const float diag = std::max(glm::length(hi - lo), 1e-6f);
  c.distance = float(p.get_real("camera.distance")) * diag;
  const std::string& view = p.get_text("camera.view");
  glm::vec3 dir(0, -1, 0), up(0, 0, 1);  // from target to eye, screen up (z-up frame)
  if (view == "top") {
    dir = {0, 0, 1};
    up = {0, 1, 0};
  } else if (view == "left") {
    dir = {-1, 0, 0};
  } else if (view == "orbit") {
    const double yaw =
        glm::radians(p.get_real("camera.yaw_deg") + p.get_real("camera.orbit_speed_deg") * time_s);
    const double pitch = glm::radians(p.get_real("camera.pitch_deg"));
    dir = glm::vec3(float(std::sin(yaw) * std::cos(pitch)), float(-std::cos(yaw) * std::cos(pitch)),
                    float(std::sin(pitch)));
  }
  c.eye = c.target + c.distance * to_world(dir, y_up);
  c.view = glm::lookAt(c.eye, c.target, to_world(up, y_up));
  const float near = std::max(c.distance - diag, 1e-3f * c.distance);
  const float far = c.distance + 2.0f * diag;
  c.proj = glm::perspective(glm::radians(float(p.get_real("camera.fov_deg"))), aspect, near, far);
  c.proj[1][1] *= -1.0f;  // Vulkan's clip space has y pointing down
  c.view_proj = c.proj * c.view;
  return c;
}

}  // namespace masav::render

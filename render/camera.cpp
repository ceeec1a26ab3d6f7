#include "render/camera.h"

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

#include "engine/scene/camera_pose.h"

namespace masav::render {

Camera make_camera(const scene::ParamSet& p, const scene::Box& box, float aspect, double time_s) {
  const scene::CameraPose pose = scene::camera_pose(p, box, time_s);
  auto vec = [](Vec3f v) { return glm::vec3(v.x, v.y, v.z); };
  Camera c;
  c.target = vec(pose.target);
  c.eye = vec(pose.eye);
  c.distance = pose.distance;
  const float diag = pose.diagonal;
  c.view = glm::lookAt(c.eye, c.target, vec(pose.up));
  const float near = std::max(c.distance - diag, 1e-3f * c.distance);
  const float far = c.distance + 2.0f * diag;
  c.proj = glm::perspective(glm::radians(pose.fov_y_deg), aspect, near, far);
  c.proj[1][1] *= -1.0f;  // Vulkan's clip space has y pointing down
  c.view_proj = c.proj * c.view;
  return c;
}

}  // namespace masav::render

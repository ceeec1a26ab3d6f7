#include "engine/scene/camera_pose.h"

#include <algorithm>
#include <cmath>

namespace masav::scene {
namespace {

constexpr double kPi = 3.14159265358979323846;

// The views are defined for a z-up world; a y-up world maps (x, y, z) -> (x, z, -y).
Vec3f to_world(Vec3f v, bool y_up) {
  return y_up ? Vec3f{v.x, v.z, -v.y} : v;
}

}  // namespace

CameraPose camera_pose(const ParamSet& p, const Box& box, double time_s) {
  const bool y_up = p.get_text("camera.up") == "y";
  CameraPose c;
  c.target = {0.5f * (box.lo.x + box.hi.x), 0.5f * (box.lo.y + box.hi.y),
              0.5f * (box.lo.z + box.hi.z)};
  const float ex = box.hi.x - box.lo.x, ey = box.hi.y - box.lo.y, ez = box.hi.z - box.lo.z;
  c.diagonal = std::max(std::sqrt(ex * ex + ey * ey + ez * ez), 1e-6f);
  c.distance = float(p.get_real("camera.distance")) * c.diagonal;
  c.fov_y_deg = float(p.get_real("camera.fov_deg"));
  const std::string& view = p.get_text("camera.view");
  Vec3f dir{0, -1, 0}, up{0, 0, 1};  // from target to eye, screen up (z-up frame)
  if (view == "top") {
    dir = {0, 0, 1};
    up = {0, 1, 0};
  } else if (view == "left") {
    dir = {-1, 0, 0};
  } else if (view == "orbit") {
    const double yaw =
        (p.get_real("camera.yaw_deg") + p.get_real("camera.orbit_speed_deg") * time_s) * kPi /
        180.0;
    const double pitch = p.get_real("camera.pitch_deg") * kPi / 180.0;
    dir = {float(std::sin(yaw) * std::cos(pitch)), float(-std::cos(yaw) * std::cos(pitch)),
           float(std::sin(pitch))};
  }
  dir = to_world(dir, y_up);
  c.eye = {c.target.x + c.distance * dir.x, c.target.y + c.distance * dir.y,
           c.target.z + c.distance * dir.z};
  c.up = to_world(up, y_up);
  return c;
}

}  // namespace masav::scene

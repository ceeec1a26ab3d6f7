#pragma once
// Where the camera of a scene's [camera] table stands: eye, target and screen-up, for the
// thesis's three fixed views (top, left, front) and the orbit camera, in a z-up or y-up world.
// One definition for the renderer's matrices (render/camera.cpp) and for the stages that
// depend on the viewpoint (the atom scenes' viewer attenuation and raymarch), so what is lit
// towards the viewer and what is drawn agree.
#include "engine/scene/param_schema.h"
#include "engine/scene/scene_view.h"

namespace masav::scene {

struct CameraPose {
  Vec3f eye, target, up;
  float distance = 1;  // eye to target
  float diagonal = 1;  // of the box
  float fov_y_deg = 40;
};

// `time_s` turns an orbit camera by camera.orbit_speed_deg per second.
CameraPose camera_pose(const ParamSet& p, const Box& box, double time_s);

}  // namespace masav::scene

#include "registry/common_tables.h"

#include "registry/scene_catalog.h"

namespace masav::scene {

const TableSchema& scene_table() {
  static const TableSchema t = [] {
    TableSchema s("scene", "which scene this file describes");
    s.choice("type", "particles", scene_type_names(), "the scene type");
    s.text("title", "", "shown in the overlay and the window title");
    return s;
  }();
  return t;
}

const TableSchema& render_table() {
  static const TableSchema t = [] {
    TableSchema s("render", "how frames are drawn (Vulkan, on any device including lavapipe)");
    s.integer("width", 960, 16, 8192, "frame width", "px");
    s.integer("height", 540, 16, 8192, "frame height", "px");
    s.choice("colormap", "viridis", {"viridis", "inferno", "thesis", "grey"},
             "colour map for the per-point scalar (thesis = blue -> green -> red)");
    s.flag("auto_range", true, "colour-map range chosen by the scene (else range_min/range_max)");
    s.real("range_min", 0.0, -1e30, 1e30, "colour-map value drawn as the map's first colour");
    s.real("range_max", 1.0, -1e30, 1e30, "colour-map value drawn as the map's last colour");
    s.real("point_size", 3.0, 0.5, 64.0, "point sprite diameter at the camera's distance", "px");
    s.choice("blend", "opaque", {"opaque", "additive"},
             "opaque sprites with depth test, or additive glow (depth-tested, not written)");
    s.choice("point_style", "spheres", {"sprites", "spheres", "surface"},
             "opaque points: flat round sprites, lit sphere impostors with their own depth, or "
             "a fluid surface (screen space: smoothed depth, thickness, refraction-like "
             "shading); additive points are always glows");
    s.real("brightness", 1.0, 0.0, 16.0,
           "multiplies the points' colour (additive: 1 shows the structure of 200K particles; "
           "the count, frame and sprite size are compensated)");
    s.flag("show_box", true, "draw the simulation box");
    s.flag("show_axes", true, "draw the x (red), y (green), z (blue) axes at the box corner");
    s.flag("overlay", true, "draw the text overlay (fps, backend, per-stage times)");
    s.choice("background", "stars", {"stars", "black"},
             "stars: a Philox star field computed on the backend; black: none");
    return s;
  }();
  return t;
}

const TableSchema& camera_table() {
  static const TableSchema t = [] {
    TableSchema s("camera", "the viewpoint");
    s.choice("view", "orbit", {"front", "top", "left", "orbit"},
             "front/top/left look along an axis (the thesis's three viewpoints); orbit uses "
             "yaw and pitch");
    s.real("yaw_deg", 35.0, -360.0, 360.0, "orbit: angle around the up axis", "deg");
    s.real("pitch_deg", 25.0, -89.0, 89.0, "orbit: elevation above the horizontal", "deg");
    s.real("distance", 1.8, 0.1, 100.0, "camera distance in box diagonals");
    s.real("fov_deg", 40.0, 5.0, 120.0, "vertical field of view", "deg");
    s.choice("up", "z", {"z", "y"}, "the world's up axis");
    s.real("orbit_speed_deg", 0.0, -360.0, 360.0,
           "orbit: yaw change per second of scene time (turntable animation)", "deg/s");
    return s;
  }();
  return t;
}

const TableSchema& run_table() {
  static const TableSchema t = [] {
    TableSchema s("run", "headless runs (masav run) and the demo's clock");
    s.integer("frames", 60, 1, 1000000, "frames to render");
    s.real("fps", 30.0, 1.0, 240.0, "frames per second of scene time (and of the MP4)", "1/s");
    s.real("start_time_s", 0.0, 0.0, 1e6, "scene time of the first frame", "s");
    return s;
  }();
  return t;
}

const TableSchema& verify_table() {
  static const TableSchema t = [] {
    TableSchema s("verify", "the cross-check run before rendering (SPEC §2)");
    s.flag("enabled", true, "cross-check every kernel the scene uses before rendering");
    s.choice("reference", "auto", {"auto", "cpu", "vulkan", "cuda"},
             "second backend (auto: the other GPU backend if present, else the CPU reference)");
    s.integer("max_points", 65536, 16, 4000000,
              "points in each kernel's check input (the scene's count, at most this)");
    return s;
  }();
  return t;
}

std::vector<const TableSchema*> common_tables() {
  return {&scene_table(), &render_table(), &camera_table(), &run_table(), &verify_table()};
}

}  // namespace masav::scene

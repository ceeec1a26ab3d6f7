#include "engine/sph/sph_presets.h"

#include <fmt/format.h>

#include <cmath>

#include "engine/core/error.h"

namespace masav {
namespace {

// The fastest speed a preset's fluid can reach from gravity: falling from the block's top to
// the floor with its initial speed, sqrt(v0^2 + 2 g H).
double fall_speed(const SphScene& s) {
  const double g =
      std::sqrt(s.gravity.x * s.gravity.x + s.gravity.y * s.gravity.y + s.gravity.z * s.gravity.z);
  const Vec3d v = s.block.velocity;
  const double fall = s.block.max.y - s.box_min.y;
  return std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z + 2.0 * g * fall);
}

// The speed of sound of a preset whose speeds come from gravity, for the default compression:
// 10 x its fall speed. At Mach 0.1 a weakly compressible fluid's density varies by about 1%
// (as M^2) in the flow and by up to about 10% (as M) at the impacts.
double sound_speed_for_fall(const SphScene& s) {
  return fall_speed(s) / kPresetMaxCompression;
}

void apply_thesis(SphScene& s, ThesisConstants t) {
  s.viscosity = t.nu * kThesisViscosityScale;
  s.kp = t.kp * kThesisKpScale;
}

// A cube of fluid dropped into a 1 m tank (Figs. 4.11-4.13: "suddenly takes off all six
// transparent planes of the inside glass cube").
SphScene cube_drop(const char* name, uint32_t n, ThesisConstants t) {
  SphScene s;
  s.preset = name;
  s.particles = n;
  s.block.min = {0.3, 0.45, 0.3};
  s.block.max = {0.7, 0.85, 0.7};
  s.sound_speed = sound_speed_for_fall(s);  // 40.8 m/s: impact at sqrt(2 g 0.85 m) = 4.1 m/s
  s.restitution = 0.3;
  s.tangential_damping = 0.01;
  apply_thesis(s, t);
  return s;
}

}  // namespace

const std::vector<SphPresetInfo>& sph_presets() {
  static const std::vector<SphPresetInfo> list = {
      {"explosion",
       "a compressed cube (1.5 x rest density) bursts in a 1 m tank (thesis Fig. 4.10)"},
      {"water", "a 0.4 m cube of water drops into a 1 m tank (thesis Figs. 4.11-4.12)"},
      {"dam-break",
       "a water column a = 0.146 m wide and 2a high collapses (Martin & Moyce 1952, "
       "Koshizuka & Oka 1996)"},
      {"mud", "the cube drop with the thesis's wet-mud viscosity (thesis Fig. 4.13)"},
      {"obstacle", "fluid thrown at a pinned heavy block of particles (thesis §4.5.1)"},
  };
  return list;
}

SphScene make_preset(std::string_view name, uint32_t n) {
  if (name == "water") return cube_drop("water", n, kThesisWater);
  if (name == "mud") return cube_drop("mud", n, kThesisMud);
  if (name == "explosion") {
    SphScene s;
    s.preset = "explosion";
    s.particles = n;
    s.block.min = {0.35, 0.35, 0.35};
    s.block.max = {0.65, 0.65, 0.65};
    s.block.density_ratio = 1.5;
    // The burst's own speeds scale with c0 (the compressed gas's internal energy is 0.2 c0^2
    // per unit mass, ~0.6 c0 once released), so no c0 keeps it at Mach 0.1: it is a gas.
    s.sound_speed = 20.0;
    s.restitution = 0.5;
    s.tangential_damping = 0.01;
    apply_thesis(s, kThesisExplosion);
    return s;
  }
  if (name == "obstacle") {
    SphScene s;
    s.preset = "obstacle";
    s.particles = n;
    s.block.min = {0.55, 0.0, 0.25};
    s.block.max = {0.95, 0.3, 0.75};
    s.block.velocity = {-1.5, 0.0, 0.0};
    s.obstacle.enabled = true;
    s.obstacle.min = {0.3, 0.0, 0.35};
    s.obstacle.max = {0.4, 0.25, 0.65};
    s.obstacle.pinned = true;
    s.sound_speed = sound_speed_for_fall(s);  // 28.4 m/s: 1.5 m/s thrown, 0.3 m fall
    s.restitution = 0.3;
    s.tangential_damping = 0.01;
    apply_thesis(s, kThesisWater);
    return s;
  }
  if (name == "dam-break") {
    // Column a wide, 2a high against the wall x = 0 (Martin & Moyce's n^2 = 2; Koshizuka & Oka's
    // a = L = 0.146 m), spanning the tank's depth; the tank is 5a long so the surge runs to
    // x = 4a before it meets the far wall. Free-slip walls (no tangential damping).
    const double a = 0.146;
    SphScene s;
    s.preset = "dam-break";
    s.particles = n;
    s.block.min = {0.0, 0.0, 0.0};
    s.block.max = {a, 2 * a, 4 * a};
    s.block.hydrostatic = true;  // the gate opens on a column at rest under its own weight
    s.box_min = {0.0, 0.0, 0.0};
    s.box_max = {5 * a, 3 * a, 4 * a};
    s.sound_speed = sound_speed_for_fall(s);  // 23.9 m/s = 10 x sqrt(2 g 2a)
    s.viscosity = 1e-3;
    s.kp = kThesisWater.kp * kThesisKpScale;
    s.restitution = 0.0;
    s.tangential_damping = 0.0;
    return s;
  }
  std::string known;
  for (const auto& p : sph_presets()) known += (known.empty() ? "" : ", ") + p.name;
  throw_invalid("sph", "preset", std::string(name), fmt::format("one of {}", known));
}

void set_max_compression(SphScene& s, double max_compression, const std::string& field) {
  if (!(max_compression >= kMinMaxCompression && max_compression <= kMaxMaxCompression))
    throw_invalid(
        "sph", field, fmt::format("{}", max_compression),
        fmt::format("a fraction in [{}, {}] (0.03: 3%)", kMinMaxCompression, kMaxMaxCompression));
  if (s.preset == "explosion")
    throw Error("", field,
                "the explosion's speeds come from its own compressed gas and grow with c0, so no "
                "speed of sound bounds its compression",
                "set its speed of sound (--sound-speed) instead");
  s.sound_speed = fall_speed(s) / max_compression;
}

}  // namespace masav

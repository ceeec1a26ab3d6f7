// A dam break stepped to t = 0.5 s on the best backend and written as a .vtp file for ParaView.
// Usage: dambreak_vtp [OUT.vtp] [PARTICLES] [T_END]
#include <masav/masav.h>

#include <cstdio>
#include <cstdlib>
#include <string>

int main(int argc, char** argv) try {
  const std::string out = argc > 1 ? argv[1] : "dambreak.vtp";
  masav::SphSceneOptions scene;
  scene.preset = "dambreak";
  scene.particles = argc > 2 ? uint32_t(std::strtoul(argv[2], nullptr, 10)) : 8192;
  const double t_end = argc > 3 ? std::strtod(argv[3], nullptr) : 0.5;

  auto backend = masav::open_backend("auto");
  auto sim = masav::make_sph(*backend, scene);
  const uint64_t steps = masav::run_sph_to(*sim, t_end);
  masav::save_sph_vtp(*sim, out);

  const masav::SphState state = sim->download();
  double top = 0;
  for (const auto& p : state.positions) top = p.y > top ? p.y : top;
  std::printf("%s: %u particles, %llu steps to t = %.3f s, highest particle at y = %.3f m -> %s\n",
              backend->name().c_str(), sim->particle_count(), (unsigned long long)steps,
              sim->time(), top, out.c_str());
  return 0;
} catch (const masav::Error& e) {
  std::fprintf(stderr, "dambreak_vtp: %s\n", e.what());
  return 2;
}

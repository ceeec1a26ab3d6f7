// A hydrogen state's electron cloud, lit from the nucleus and raymarched to a PNG, headless, on
// the best backend. Usage: atom_png [OUT.png] [STATE] [PARTICLES]
#include <masav/masav.h>

#include <cstdio>
#include <cstdlib>
#include <string>

int main(int argc, char** argv) try {
  const std::string out = argc > 1 ? argv[1] : "atom.png";
  masav::AtomOptions options;
  options.state = argc > 2 ? argv[2] : "state3";
  options.particles = argc > 3 ? uint32_t(std::strtoul(argv[3], nullptr, 10)) : 200000;

  auto backend = masav::open_backend("auto");
  const masav::Image image = masav::render_atom(*backend, options, 320, 320);
  masav::save_png(out, image);

  double lit = 0;
  for (const auto& p : image.pixels) lit += p.w;
  std::printf("%s: %s, %u particles, %ux%u image, mean alpha %.4f -> %s\n", backend->name().c_str(),
              options.state.c_str(), options.particles, image.width, image.height,
              lit / double(image.pixels.size()), out.c_str());
  return 0;
} catch (const masav::Error& e) {
  std::fprintf(stderr, "atom_png: %s\n", e.what());
  return 2;
}

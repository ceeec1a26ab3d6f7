#include <fmt/format.h>

#include <cmath>

#include "engine/core/error.h"

#include "engine/atom/orbital.h"
#include "engine/atom/orbital_tables.h"
#include "engine/volume/transfer_function.h"
#include "masav/atom.h"

namespace masav {

std::unique_ptr<atom::AtomScene> make_atom(Backend& backend, const AtomOptions& options) {
  atom::AtomSceneOptions o;
  o.state = atom::preset_state(options.state);
  o.state.real = options.real;
  atom::validate_state(o.state, "masav::make_atom");
  o.particles = options.particles;
  o.seed = options.seed;
  o.volume_dims = options.volume_dims;
  o.use_cache = options.use_cache;
  o.cache_dir = options.cache_dir;
  // The viewer where the camera is, as `masav atom` places it for the view.
  const float half = float(atom::box_half_width(o.state, o.box_probability));
  o.viewer = atom::view_eye(atom::parse_view(options.view), 1.9f * half * std::sqrt(3.0f));
  return std::make_unique<atom::AtomScene>(backend, o);
}

Image render_atom(Backend& backend, const AtomOptions& options, uint32_t width, uint32_t height) {
  if (width < 1 || width > 16384 || height < 1 || height > 16384)
    throw_invalid("masav::render_atom", "width x height", fmt::format("{}x{}", width, height),
                  "from 1 to 16384 pixels each");
  auto scene = make_atom(backend, options);
  scene->run_all();
  const RaymarchParams rp =
      atom::default_raymarch(scene->volume(), atom::parse_view(options.view), width, height);
  return {width, height,
          atom::render_volume(backend, scene->volume(), scene->sample,
                              volume::resample_transfer(volume::default_transfer_points()), rp)};
}

}  // namespace masav

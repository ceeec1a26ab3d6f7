#include "engine/atom/atom_scene_types.h"

#include <algorithm>

#include "engine/atom/atom_scene_graph.h"
#include "engine/atom/atom_schema.h"
#include "engine/atom/orbital_tables.h"
#include "engine/grid/hash_grid.h"

namespace masav::atom {
namespace {

using scene::ParamSet;

// The kernels the cloud and its light run: sampling, the density grid (hash grid + density),
// the scattering table (when not cached, and always in the check), the two lighting passes.
std::vector<KernelId> cloud_kernels() {
  return {KernelId::orbital_sample,    KernelId::grid_assign_cells, KernelId::radix_sort,
          KernelId::grid_cell_ranges,  KernelId::cloud_density,     KernelId::scatter_table,
          KernelId::nebula_illuminate, KernelId::nebula_view};
}

scene::CheckInputs check_inputs_of(const ParamSet& p) {
  scene::CheckInputs c;
  c.points = uint32_t(std::min(p.get_int("atom.count"), p.get_int("verify.max_points")));
  c.seed = uint64_t(p.get_int("atom.seed"));
  // The hash-grid checks run on the scene's density grid.
  const float h = float(box_half_width(state_of(p), p.get_real("nebula.box_probability")));
  const uint32_t d = uint32_t(p.get_int("nebula.density_dims"));
  c.grid = make_grid_params({-h, -h, -h}, 2 * h / float(d), {d, d, d}, c.points);
  c.params = p;
  return c;
}

}  // namespace

scene::SceneType atom_scene_type() {
  scene::SceneType t;
  t.name = "atom";
  t.help = "a hydrogen electron cloud lit as a reflection nebula, drawn as particles";
  t.tables = {&atom_table(), &nebula_table(), &scatter_table_schema()};
  t.kernels = [](const ParamSet&) { return cloud_kernels(); };
  t.check_inputs = check_inputs_of;
  t.make = [](Backend& b, const ParamSet& p, const scene::SceneHost& host) {
    return make_atom_scene(b, p, false, host.cache_dir);
  };
  return t;
}

scene::SceneType atom_volume_scene_type() {
  scene::SceneType t;
  t.name = "atom-volume";
  t.help = "the lit electron cloud voxelized and raymarched (optionally with its particles)";
  t.tables = {&atom_table(), &nebula_table(), &scatter_table_schema(), &volume_table()};
  t.kernels = [](const ParamSet&) {
    std::vector<KernelId> k = cloud_kernels();
    k.insert(k.end(), {KernelId::voxelize, KernelId::volume_bricks, KernelId::volume_brick_skip,
                       KernelId::raymarch});
    return k;
  };
  t.check_inputs = check_inputs_of;
  t.make = [](Backend& b, const ParamSet& p, const scene::SceneHost& host) {
    return make_atom_scene(b, p, true, host.cache_dir);
  };
  return t;
}

}  // namespace masav::atom

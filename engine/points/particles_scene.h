#pragma once
// The `particles` demo scene: a Philox point cloud drifting through a periodic box, binned with
// the hash grid and coloured by its neighbour count -- the foundation's kernels end to end,
// from sampling to the screen.
//
// Stages (inputs in brackets):
//   start_uniforms      philox_uniform   [particles.count, particles.seed]
//   direction_uniforms  philox_uniform   [particles.count, particles.seed]
//   drift_points        drift_points     [both uniforms, box_size, drift_speed, time]
//   hash_grid           assign + radix sort + cell ranges   [drift_points, grid_cells]
//   reorder             gather           [hash_grid]
//   neighbor_counts     grid_count_neighbors  [reorder, neighbor_radius]
//   stars               philox_uniform   [render.width, render.height, particles.seed]
// color_by = neighbors reaches the grid stages; any other colouring never creates them.
// background = stars reaches the star field; black never creates it.
#include "engine/scene/scene.h"

namespace masav::points {

const scene::TableSchema& particles_table();
scene::SceneType particles_scene_type();

}  // namespace masav::points

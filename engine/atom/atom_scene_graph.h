#pragma once
// The electron-cloud scenes as a stage graph over the shared atom pipeline (atom_scene.h).
//
// Stages (inputs in brackets):
//   cloud          orbital_sample        [atom.*]
//   density        hash grid + cloud_density  [cloud, nebula.density_dims, box_probability]
//   scatter_table  scatter_table or the disk cache  [scatter.*]
//   illuminate     nebula_illuminate at 250K lm  [density, nebula.tau_peak/path/step_a0,
//                                                 scatter.albedo]
//   viewer         nebula_view towards the camera  [illuminate, scatter_table, view]
//   light          host: exposure * Phi / 250K lm  [viewer, nebula.power_lm, nebula.exposure]
// atom-volume adds:
//   voxelize       voxelize (light scaled by the light stage)  [light, volume.dims/s/t]
//   transfer       the transfer function's table  [volume.transfer_file, volume.transfer]
//   bricks         volume_bricks + volume_brick_skip  [voxelize, transfer]
//   raymarch       raymarch with the camera  [bricks, view, render.width/height,
//                                            volume.step_voxels/compositing]
// An edited transfer function (volume.transfer) reruns transfer, bricks and raymarch only.
// Light is linear in Phi, so a power change reruns only `light` (and, in atom-volume, the
// volume that shows it); a camera change reruns the viewer attenuation and what reads it; the
// scattering table comes from the disk cache once computed. The `atom` scene never reaches the
// volume stages: they are never created.
#include <memory>
#include <string>

#include "engine/scene/scene.h"

namespace masav::atom {

// cache_dir: the scattering table's cache (AtomSceneOptions::cache_dir; "" = none).
std::unique_ptr<scene::SceneInstance> make_atom_scene(Backend& b, const scene::ParamSet& p,
                                                      bool volume, const std::string& cache_dir);

}  // namespace masav::atom

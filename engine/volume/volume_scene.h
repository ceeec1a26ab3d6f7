#pragma once
// The scene type `volume`: a scalar volume from a file (raw with dims and type, NRRD, VTI),
// raymarched from the scene's camera through a transfer function. The demo's "Open" makes one;
// a scene file can name one too. Tables: [source] (the file and the options of `masav volume`
// that read it) and [raymarch] (transfer function, step, compositing, gain).
//
// Stages (inputs in brackets):
//   load      the file, uploaded   [source.*]
//   transfer  the transfer function's tables  [raymarch.transfer_file, raymarch.transfer]
//   bricks    volume_bricks + volume_brick_skip  [load, transfer]
//   raymarch  raymarch with the camera  [bricks, view, render.width/height,
//                                        raymarch.step_voxels/compositing/preintegrate]
#include "engine/scene/scene.h"
#include "engine/volume/volume_file.h"

namespace masav::volume {

scene::SceneType volume_scene_type();

// The [source] table's keys to and from the options `masav volume` takes.
VolumeFileOptions volume_file_options(const scene::ParamSet& p);
void set_volume_file_options(scene::ParamSet& p, const VolumeFileOptions& o);

}  // namespace masav::volume

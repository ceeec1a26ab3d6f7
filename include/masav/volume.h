#pragma once
/// \file
/// Volumes: files read as `masav volume` reads them (NRRD `.nrrd`/`.nhdr`, VTK `.vti`, raw with
/// its dimensions and sample type), scalar volumes (`volume::ScalarVolume`, x fastest), and the
/// raymarch of a volume through a transfer function to an image on any backend.
#include <cstdint>
#include <string>
#include <vector>

#include "engine/core/types.h"
#include "engine/kernels/backend.h"
#include "engine/volume/volume_file.h"
#include "masav/image.h"

namespace masav {

/// Reads a volume file: the format from the extension (`.nrrd`/`.nhdr`, `.vti`; a raw file
/// needs `options.dims` and `options.type`). Throws masav::Error naming the file and the field
/// that is wrong.
volume::ScalarVolume read_volume(const volume::VolumeFileOptions& options);

/// Reads a NRRD or VTK image file by its path.
volume::ScalarVolume read_volume(const std::string& path);

/// How to raymarch a volume.
struct RaymarchOptions {
  uint32_t width = 256;       ///< image width, 1 to 16384 pixels
  uint32_t height = 256;      ///< image height, 1 to 16384 pixels
  std::string view = "front"; ///< camera preset: front, top or left
  float step_voxels = 0.5f;   ///< ray step in voxels, (0, 16]
  bool lerp = false;          ///< the thesis's lerp compositing instead of front-to-back
  bool preintegrate = false;  ///< pre-integrated transfer function (no slab artefacts)
  /// The transfer function, RGBA in [0, 1] over the volume's value range (2 to 4096 entries);
  /// empty: the default of `masav volume`.
  std::vector<Vec4d> transfer;
};

/// Raymarches `volume` on `backend` (uploaded, marched, downloaded). Throws masav::Error naming
/// the option out of range.
Image raymarch(Backend& backend, const volume::ScalarVolume& volume,
               const RaymarchOptions& options = {});

/// The same with every knob of the raymarch kernel given (`params`: the camera, the image size,
/// the step, compositing, clipping; its `volume` is set from `volume`), for callers that place
/// their own camera; `transfer` as RaymarchOptions::transfer.
Image raymarch(Backend& backend, const volume::ScalarVolume& volume, RaymarchParams params,
               const std::vector<Vec4d>& transfer = {});

}  // namespace masav

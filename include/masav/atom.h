#pragma once
/// \file
/// The hydrogen atom's electron cloud: particles sampled from |psi_nlm|^2, a density grid, the
/// Monte Carlo scattering table, the nucleus's light through the cloud, and the voxelized
/// volume raymarched to an image. `atom::AtomScene` (engine/atom/atom_scene.h) runs the stages
/// one by one and holds each stage's buffers; render_atom() runs them all.
#include <cstdint>
#include <memory>
#include <string>

#include "engine/atom/atom_scene.h"
#include "engine/kernels/backend.h"
#include "masav/image.h"

namespace masav {

/// The atom scene's main options (the rest keep the defaults of `masav atom`).
struct AtomOptions {
  std::string state = "state1";  ///< a preset, "state1" to "state10" (masav atom --list)
  bool real = false;             ///< the real orbital instead of the complex one
  uint32_t particles = 200000;   ///< cloud particles
  uint64_t seed = 1;             ///< seed of the sampling
  uint32_t volume_dims = 60;     ///< voxels per axis of the raymarched volume
  std::string view = "front";    ///< camera preset: front, top or left
  bool use_cache = true;         ///< reuse the scattering table from the cache directory
  /// The scattering table's cache directory (the table goes in its `scatter/`); empty: no
  /// cache, the table is computed every time. The `masav` command line passes the directory
  /// MASAV_CACHE_DIR, XDG_CACHE_HOME or HOME names (docs/atom.md).
  std::string cache_dir;
};

/// The atom scene for `options` on `backend`, its stages not yet run.
std::unique_ptr<atom::AtomScene> make_atom(Backend& backend, const AtomOptions& options = {});

/// Every stage run and the volume raymarched from the options' view to a width x height image.
Image render_atom(Backend& backend, const AtomOptions& options, uint32_t width, uint32_t height);

}  // namespace masav

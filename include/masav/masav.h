#pragma once
/// \file
/// The whole public API of masav in one include.
///
/// \mainpage masav
/// masav computes physics on interchangeable backends -- the CPU reference in double
/// precision, Vulkan compute (any vendor, and lavapipe on a CPU), CUDA -- that implement one
/// kernel set and are cross-checked against each other. The API:
///  - version.h: MASAV_VERSION and masav::version();
///  - error.h: masav::Error, the one exception type;
///  - backends.h: open a backend by name and options, list what this machine has;
///  - kernels.h: every kernel as a method of masav::Backend, typed buffers;
///  - cross_check.h: a kernel on two backends, compared, with the report `masav verify` prints;
///  - sph.h: SPH simulations, their runs, checkpoints and snapshots;
///  - volume.h and image.h: volume files, the raymarch to an image, PNG output;
///  - atom.h: the hydrogen atom's electron cloud, lit and raymarched;
///  - scene.h: scene files, their overrides and cross-checks;
///  - scene_render.h: scene files rendered headless, frame by frame, to RGBA frames and PNGs.
///
/// Build against the installed package with `find_package(masav 0.2 CONFIG REQUIRED)` and
/// `target_link_libraries(app PRIVATE masav::masav)` (docs/library.md).
#include "masav/atom.h"
#include "masav/backends.h"
#include "masav/cross_check.h"
#include "masav/error.h"
#include "masav/image.h"
#include "masav/kernels.h"
#include "masav/scene.h"
#include "masav/scene_render.h"
#include "masav/sph.h"
#include "masav/version.h"
#include "masav/volume.h"

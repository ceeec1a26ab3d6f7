// The compute kernels' specialisation constants, one id per meaning, for the shaders
// (`layout(constant_id = kSpecSphModel) const uint SPH_MODEL = 0u;`) and for the Vulkan backend,
// which sets them by these names (compute/vk_variants.h). Ids 0-2 every kernel has
// (shaders/common/kernel_base.glsl); each other id is read by the shaders named beside it, and a
// kernel sets only those its shader reads. A new meaning takes a new id at the end; a shader
// never reuses another meaning's id. Compiles as C++ and as GLSL (engine/core/layout.h).
#ifndef MASAV_SHADERS_SPEC_IDS_H
#define MASAV_SHADERS_SPEC_IDS_H

#include "engine/core/layout.h"

// X(name, id) for each: the only list of the ids.
#define MASAV_SPEC_IDS(X)                                                                          \
  X(kSpecWorkgroupSize, 0)   /* WG_SIZE = local_size_x: every kernel */                            \
  X(kSpecSubgroupMin, 1)     /* SUBGROUP_MIN, the smallest subgroup the device may use */          \
  X(kSpecCountLoopTicks, 2)  /* COUNT_LOOP_TICKS: loop counting (tests of the loop limit) */       \
  X(kSpecItems, 3)           /* ITEMS per invocation of a tile: radix_*, scan_tiles, scan_add* */  \
  X(kSpecHasValues, 4)       /* HAS_VALUES, the sort moves values with its keys: radix_scatter* */ \
  X(kSpecScatterEntries, 5)  /* ENTRIES per tau row: scatter_table */                              \
  X(kSpecRayModes, 6)        /* RAY_MODES, its kRayModeFlags bits: raymarch */                     \
  X(kSpecRayBrick, 7)        /* RAY_BRICK, the brick's edge in voxels: raymarch */                 \
  X(kSpecRayPow, 8)          /* RAY_POW, the opacity correction's power: raymarch */               \
  X(kSpecVolumeQuads, 9)     /* VOLUME_QUADS, the volume four voxels to a texel: raymarch */       \
  X(kSpecSphModel, 10)       /* SPH_MODEL, SphPressureModel: sph.glsl */                           \
  X(kSpecSphCoopWalk, 11)    /* SPH_COOP_WALK, rows walked by subgroup clusters: sph_coop.glsl */  \
  X(kSpecSphWallSplit, 12)   /* SPH_WALL_SPLIT, the walk split at the walls: sph_walk.glsl */      \
  X(kSpecSphReach, 13)       /* SPH_REACH, SphReach: sph_density */                                \
  X(kSpecSphImagesAfter, 14) /* SPH_IMAGES_AFTER, wall images after the walk: sph_forces */        \
  X(kSpecSphState, 15)       /* SPH_STATE, the neighbour state bound: sph_density, sph_forces */

#define MASAV_SPEC_ID_CONSTANT(name, id) MASAV_CONSTANT(name, id)

MASAV_NAMESPACE_BEGIN
MASAV_SPEC_IDS(MASAV_SPEC_ID_CONSTANT)
MASAV_NAMESPACE_END

#ifdef __cplusplus
namespace masav {
struct SpecIdName {
  const char* name;
  uint32_t id;
};
#define MASAV_SPEC_ID_ENTRY(name, id) SpecIdName{#name, id},
// Every id with its name, in the order above.
inline constexpr SpecIdName kSpecIds[] = {MASAV_SPEC_IDS(MASAV_SPEC_ID_ENTRY)};
#undef MASAV_SPEC_ID_ENTRY
// One id per meaning: the ids are 0, 1, 2, ... in the order above.
static_assert(
    [] {
      for (uint32_t i = 0; i < sizeof(kSpecIds) / sizeof(kSpecIds[0]); ++i)
        if (kSpecIds[i].id != i) return false;
      return true;
    }(),
    "shaders/spec_ids.h: each id once, numbered in order");
// The first id a kernel's own variant may set (0-2 are set for every kernel).
inline constexpr uint32_t kSpecFirstVariant = kSpecItems;
}  // namespace masav
#endif

#endif

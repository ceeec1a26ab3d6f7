#pragma once
// Checkpoints of an SPH run: the scene and the SphResumeState in one binary file, from which a
// simulation continues the same trajectory (bit for bit on the same backend).
//
// Format (little-endian; version kSphCheckpointVersion):
//   "MASAVSPH" (8 bytes), u32 format version, u32 section count (3),
//   u32 length + bytes of the writing masav's version (at most 64),
//   then the sections SCEN (the scene, field by field), STAT (particle count and the host's
//   step control) and PART (the per-particle arrays), each as
//   u32 tag, u32 0, u64 payload bytes, u64 FNV-1a 64 of the payload, payload.
// An array is a u64 count and its values. Reading checks every size against the bytes left
// before allocating and every checksum before parsing; each failure names the file, the field
// and what was expected. Writing goes to a temporary file in the same directory, fsync'd, then
// renamed over the old checkpoint (which stays whole until the new one is).
#include <cstdint>
#include <span>
#include <string>

#include "engine/sph/sph_params.h"
#include "engine/sph/sph_simulation.h"

namespace masav {

// 2: the open block of run(); 3: the stats the next block's dt comes from (lag_stats).
inline constexpr uint32_t kSphCheckpointVersion = 3;
inline constexpr uint32_t kSphCheckpointMaxParticles = 1u << 30;  // the scene's own bound

struct SphCheckpoint {
  std::string writer;  // masav version that wrote it
  SphScene scene;
  SphResumeState state;
};

void write_sph_checkpoint(const std::string& path, const SphScene& scene,
                          const SphResumeState& state);
// The simulation's scene and state.
void write_sph_checkpoint(const std::string& path, SphSimulation& sim);
SphCheckpoint read_sph_checkpoint(const std::string& path);

// The first scene field (its name) in which a and b differ; empty when none does.
std::string sph_scene_difference(const SphScene& a, const SphScene& b);
// Restores `c` into `sim`, refusing a checkpoint of another scene (naming the field) or
// particle count. `path` names the file in the errors.
void restore_sph_checkpoint(SphSimulation& sim, const SphCheckpoint& c, const std::string& path);

// FNV-1a 64 over the bytes (the sections' checksum).
uint64_t fnv1a64(std::span<const uint8_t> bytes);

}  // namespace masav

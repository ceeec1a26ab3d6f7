#pragma once
// The three sections of an SPH checkpoint (format in sph_checkpoint.h): SCEN, the scene field by
// field; STAT, the particle count and the host's step control; PART, the per-particle arrays.
// Their payloads written, and read back into a checkpoint with every field checked.
#include <cstdint>
#include <string>
#include <vector>

#include "engine/sph/sph_checkpoint.h"

namespace masav::checkpoint_io {

std::vector<uint8_t> scene_bytes(const SphScene& s);
std::vector<uint8_t> state_bytes(const SphResumeState& r);
std::vector<uint8_t> particle_bytes(const SphResumeState& r);

// The scene and the state of `c` from the payloads of SCEN, STAT and PART (checksums checked
// already); `path` names the file in the errors.
void read_sections(const std::vector<uint8_t> (&payload)[3], const std::string& path,
                   SphCheckpoint& c);

}  // namespace masav::checkpoint_io

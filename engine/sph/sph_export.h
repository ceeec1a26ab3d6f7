#pragma once
// Particles as VTK PolyData (.vtp) for ParaView: position, velocity, density, pressure, id and
// inverse mass (1 fluid, 0 pinned obstacle). Written to a temporary name and renamed. On several
// ranks each rank writes its particles as one piece and rank 0 the index (.pvtp) naming them.
#include <string>
#include <vector>

#include "engine/sph/sph_simulation.h"

namespace masav {

// `s` in particle-id order (ids 0 to n - 1).
void write_sph_vtp(const std::string& path, const SphState& s);
// A piece: the particles of `s`, in any order, with their ids.
void write_sph_vtp(const std::string& path, const SphState& s, const std::vector<uint32_t>& ids);
// The index of the pieces (their file names, relative to the .pvtp's directory).
void write_sph_pvtp(const std::string& path, const std::vector<std::string>& pieces);

}  // namespace masav

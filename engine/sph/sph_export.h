#pragma once
// Particles as VTK PolyData (.vtp) for ParaView: position, velocity, density, pressure, id and
// inverse mass (1 fluid, 0 pinned obstacle). Written to a temporary name and renamed.
#include <string>

#include "engine/sph/sph_simulation.h"

namespace masav {

void write_sph_vtp(const std::string& path, const SphState& s);

}  // namespace masav

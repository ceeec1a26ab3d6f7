#pragma once
// The SPH kernels called with their buffers grouped by role (SphDensityIO, SphForcesIO,
// SphIntegrateIO), as the simulation, the cross-check and the tests hold them. A missing
// required buffer is an error naming it, before the kernel's own checks.
#include "engine/grid/hash_grid.h"
#include "engine/kernels/backend.h"

namespace masav {

// The view of `grid` the SPH and DFSPH kernels walk; they refuse one whose tables are not the
// counting build's (HashGrid::prefix_ranges).
SphGridView sph_grid_view(const HashGrid& grid);

void sph_density(Backend& b, const SphStepParams& p, const SphDensityIO& io);
void sph_forces(Backend& b, const SphStepParams& p, const SphForcesIO& io);
void sph_integrate(Backend& b, const SphIntegrateParams& p, const SphIntegrateIO& io);

// The DFSPH kernels (engine/kernels/dfsph_params.h): the buffers each reads or writes must be
// given in `io`.
void dfsph_factor(Backend& b, const DfsphParams& p, const DfsphIO& io);
void dfsph_rate(Backend& b, const DfsphParams& p, const DfsphIO& io);
void dfsph_correct(Backend& b, const DfsphParams& p, const DfsphIO& io);

}  // namespace masav

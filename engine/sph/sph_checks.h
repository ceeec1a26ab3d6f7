#pragma once
// Validation of the SPH kernels' parameters and buffers, shared by every backend so that each
// rejects the same input with the same message (field, value, allowed range).
#include "engine/core/backend.h"

namespace masav {

void check_sph_step(const DeviceApi& dev, const SphStepParams& p, const char* kernel);
void check_sph_density(const DeviceApi& dev, const SphStepParams& p, const SphDensityIO& io);
void check_sph_forces(const DeviceApi& dev, const SphStepParams& p, const SphForcesIO& io);
void check_sph_integrate(const DeviceApi& dev, const SphIntegrateParams& p,
                         const SphIntegrateIO& io);

}  // namespace masav

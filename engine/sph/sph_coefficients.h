#pragma once
// The equation of state on the host, in double, for the diagnostics (the kernels' coefficients
// are device_params in engine/kernels/sph_kernel_params.h).
#include "engine/kernels/sph_kernel_params.h"

namespace masav {

// Tait pressure and the internal energy per unit mass it stores, e(rho) = int_rho0^rho p/r^2 dr
// (zero at rest density; with the clamp, zero below it), in double for the diagnostics.
double tait_pressure(double rho, const SphStepParams& p);
double tait_internal_energy(double rho, const SphStepParams& p);

}  // namespace masav

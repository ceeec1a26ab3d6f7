#pragma once
// The SPH kernels' constants (engine/kernels/sph_kernels.h), computed once on the host in double
// from SphStepParams; GPU backends round them to fp32.
#include "engine/kernels/sph_kernels.h"
#include "engine/sph/sph_kernel_params.h"

namespace masav {

sph::Coefficients<double> make_coefficients(const SphStepParams& p);
sph::Coefficients<float> to_float(const sph::Coefficients<double>& c);

// Signal speed of the pressure model (m/s): c0 for wcsph; for the thesis model, whose force
// kp m sum (rho_j - rho_i)/(2 rho_j) grad W_thesis approximates -(3/14) kp h grad rho (the
// continuum moment of Eq. 4.7's kernel), the sound speed of that isothermal gas,
// sqrt(3/14 kp rho0 h). Used by the CFL limit and to report a thesis-model pressure
// c^2 (rho - rho0).
double signal_speed(const SphStepParams& p);

// Tait pressure and the internal energy per unit mass it stores, e(rho) = int_rho0^rho p/r^2 dr
// (zero at rest density; with the clamp, zero below it), in double for the diagnostics.
double tait_pressure(double rho, const SphStepParams& p);
double tait_internal_energy(double rho, const SphStepParams& p);

}  // namespace masav

#pragma once
// Single scattering in the thesis's sphere by quadrature, independent of the Monte Carlo code:
// the exact limit the table approaches as tau -> 0, and exactly what scatter_table computes with
// max_scatterings = 1 (tests and benchmarks).
#include <cstdint>
#include <vector>

namespace masav::atom {

// Photons entering at z = -1 along +z (ScatterStart::surface), scattering once at depth s
// (pdf tau e^{-tau s}), Henyey-Greenstein g, then leaving unscattered: the probability of
// leaving into each of `bins` bins of cos(angle to +z), without the albedo factor:
//   int_0^2 tau e^{-tau s} int_bin p_HG(mu) e^{-tau L(s, mu)} dmu ds,
// L the distance from (0, 0, s - 1) along mu to the unit sphere.
std::vector<double> single_scattering(double tau, double g, uint32_t bins);

double henyey_greenstein_pdf(double g, double mu);

}  // namespace masav::atom

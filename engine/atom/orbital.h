#pragma once
// Hydrogen states (n, l, m), complex or real, their validation, the thesis's presets (Table 2.1),
// the wave function in double precision, and the closed-form expectation values the tests and
// benchmarks compare sampled clouds against.
#include <string>
#include <string_view>
#include <vector>

namespace masav::atom {

constexpr int kMaxN = 16;  // the recurrences are checked to ~1e-12 up to here (tests: n <= 16)

struct OrbitalState {
  int n = 1;
  int l = 0;
  int m = 0;
  bool real =
      false;  // real orbitals: cos(m phi) (m > 0) or sin(|m| phi) (m < 0) instead of e^{imphi}
};

// Throws masav::Error naming the field (n, l or m), its value and the allowed range.
void validate_state(const OrbitalState& s, std::string_view where = "orbital");
// "state1" .. "state10" (thesis Table 2.1); throws for any other name, listing the valid ones.
OrbitalState preset_state(std::string_view name);
const std::vector<std::string>& preset_names();
std::string describe(const OrbitalState& s);  // e.g. "n=3 l=2 m=0 (complex)"

double radial_log_norm(int n, int l);  // log N_nl
double radial_R(int n, int l, double r_a0);
// Angular factor |Y|^2 at (cos theta, phi).
double angular_density(const OrbitalState& s, double cos_theta, double phi);
// |psi|^2 in a0^-3 at spherical coordinates.
double density(const OrbitalState& s, double r_a0, double cos_theta, double phi);
// Largest |psi|^2 over space (a fine search; used to scale optical depths between states).
double peak_density(const OrbitalState& s);

// Closed forms (Bethe & Salpeter): <r> = (3n^2 - l(l+1)) / 2, <r^2> = n^2 (5n^2 + 1 - 3l(l+1)) / 2,
// <1/r> = 1/n^2; <cos^2 theta> of |Y_lm|^2 = (2l^2 + 2l - 1 - 2m^2) / ((2l - 1)(2l + 3)).
double expect_r(int n, int l);
double expect_r2(int n, int l);
double expect_inv_r(int n);
double expect_cos2(int l, int m);
// Radial nodes (n - l - 1 of them): the roots of L_{n-l-1}^{2l+1}(2r/n), ascending, to 1e-12.
std::vector<double> radial_nodes(int n, int l);

}  // namespace masav::atom

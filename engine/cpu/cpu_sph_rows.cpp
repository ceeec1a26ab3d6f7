#include "engine/cpu/cpu_sph_rows.h"

namespace masav::cpu {

#if defined(__GNUC__) && defined(__x86_64__) && !defined(__clang__)
#define MASAV_CPU_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define MASAV_CPU_CLONES
#endif

MASAV_CPU_CLONES
void density_row(const double* xs, const double* ys, const double* zs, uint32_t count, double px,
                 double py, double pz, double inv_h2, double& sum, uint32_t& within) {
  double s[4] = {0, 0, 0, 0};
  uint32_t c[4] = {0, 0, 0, 0};
  uint32_t k = 0;
  for (; k + 4 <= count; k += 4) {
    for (uint32_t l = 0; l < 4; ++l) {
      const double dx = px - xs[k + l], dy = py - ys[k + l], dz = pz - zs[k + l];
      const double q2 = ((dx * dx + dy * dy) + dz * dz) * inv_h2;
      const double u0 = 1.0 - q2;
      const double u = u0 > 0.0 ? u0 : 0.0;
      s[l] += u * u * u;
      c[l] += q2 < 1.0 ? 1u : 0u;
    }
  }
  for (; k < count; ++k) {
    const double dx = px - xs[k], dy = py - ys[k], dz = pz - zs[k];
    const double q2 = ((dx * dx + dy * dy) + dz * dz) * inv_h2;
    const double u0 = 1.0 - q2;
    const double u = u0 > 0.0 ? u0 : 0.0;
    s[0] += u * u * u;
    c[0] += q2 < 1.0 ? 1u : 0u;
  }
  sum += (s[0] + s[1]) + (s[2] + s[3]);
  within += (c[0] + c[1]) + (c[2] + c[3]);
}

MASAV_CPU_CLONES
uint32_t neighbors_row(const double* xs, const double* ys, const double* zs, uint32_t first,
                       uint32_t count, double px, double py, double pz, double h2, uint32_t self,
                       uint32_t* out) {
  uint32_t n = 0;
  for (uint32_t k = 0; k < count; ++k) {
    const double dx = px - xs[k], dy = py - ys[k], dz = pz - zs[k];
    const double r2 = (dx * dx + dy * dy) + dz * dz;
    const uint32_t j = first + k;
    out[n] = j;
    n += (r2 < h2) & (j != self) ? 1u : 0u;
  }
  return n;
}

}  // namespace masav::cpu

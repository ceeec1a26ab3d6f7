// orbital_sample's per-particle body: the GLSL twin of engine/kernels/orbital_math.h. Reads the
// tables from a buffer `tables[]` that the including kernel declares.
const float ORBITAL_PI = 3.14159265358979323846;

// The largest k in [0, bins) with tables[base + k] <= u (integer compares: the same bin as the
// C++ and CUDA code).
uint cdf_search(uint base, uint bins, uint u) {
  uint lo = 0u, hi = bins;
  for (int it = 0; it < 32 && hi - lo > 1u; ++it) {
    LOOP_TICK();
    const uint mid = (lo + hi) >> 1;
    if (tables[base + mid] <= u) lo = mid;
    else hi = mid;
  }
  return lo;
}

float cdf_invert(uint base, uint bins, uint u, float x0, float range) {
  const uint k = cdf_search(base, bins, u);
  const uint lo = tables[base + k], hi = tables[base + k + 1u];
  const float t = (float(u - lo) + 0.5) / float(hi - lo);
  return x0 + (float(k) + t) * (range / float(bins));
}

vec3 spherical_to_cartesian(float r, float cos_theta, float phi) {
  const float sin_theta = sqrt(max(0.0, 1.0 - cos_theta * cos_theta));
  return vec3(r * sin_theta * cos(phi), r * sin_theta * sin(phi), r * cos_theta);
}

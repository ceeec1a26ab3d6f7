// One photon of scatter_table: the GLSL twin of engine/kernels/scatter_math.h (see there for the
// model, the corrected direction update and the fixed-point tallies). Needs philox.glsl and
// engine/kernels/atom_params.h.
const float SCATTER_PI = 3.14159265358979323846;

float hg_cos_theta(float g, float v) {
  if (abs(g) < 1e-6) return 2.0 * v - 1.0;
  const float q = (1.0 - g * g) / (1.0 - g + 2.0 * g * v);
  return clamp((1.0 + g * g - q * q) / (2.0 * g), -1.0, 1.0);
}

vec3 scatter_direction(vec3 d, float cos_theta, float phi) {
  const float st = sqrt(max(0.0, 1.0 - cos_theta * cos_theta));
  const float cp = cos(phi), sp = sin(phi);
  if (abs(d.z) > 0.9999) return vec3(st * cp, st * sp, (d.z > 0.0 ? 1.0 : -1.0) * cos_theta);
  const float zeta = sqrt(1.0 - d.z * d.z);
  const vec3 n = vec3(st / zeta * (d.x * d.z * cp - d.y * sp) + d.x * cos_theta,
                      st / zeta * (d.y * d.z * cp + d.x * sp) + d.y * cos_theta,
                      -zeta * st * cp + d.z * cos_theta);
  return n * (1.0 / sqrt(dot(n, n)));
}

float sphere_exit(vec3 x, vec3 d) {
  const float b = dot(x, d), c = dot(x, x) - 1.0;
  return -b + sqrt(max(0.0, b * b - c));
}

uint cos_bin(float mu, uint bins) {
  const float x = (clamp(mu, -1.0, 1.0) + 1.0) * (float(bins) * 0.5);
  const uint b = uint(x);
  return b < bins ? b : bins - 1u;
}

struct PhotonOutcome {
  uint entry;
  uint scatterings;
  float weight;
};

struct PhotonSetup {
  vec3 d0;  // unit
  bool from_centre;
  float g, albedo, threshold;
  uint max_scatterings, bins;
  uvec2 seed;
};

PhotonOutcome trace_photon(PhotonSetup s, float tau, uvec2 stream) {
  vec3 x = s.from_centre ? vec3(0.0) : -s.d0;
  vec3 d = s.d0;
  float w = 1.0;
  for (uint k = 0u; k <= s.max_scatterings; ++k) {
    LOOP_TICK();
    const uvec4 b = philox_stream_block(s.seed, stream, uvec2(0u), k);
    const float optical = -log(1.0 - philox_u01(b.x));
    if (optical >= tau * sphere_exit(x, d))
      return PhotonOutcome(cos_bin(dot(d, s.d0), s.bins), k, w);
    if (k == s.max_scatterings) return PhotonOutcome(s.bins + kScatterCapped, k, w);
    x += d * (optical / tau);
    w *= s.albedo;
    if (w < s.threshold) return PhotonOutcome(s.bins + kScatterThreshold, k + 1u, w);
    const float ct = hg_cos_theta(s.g, philox_u01(b.y));
    d = scatter_direction(d, ct, 2.0 * SCATTER_PI * philox_u01(b.z));
  }
  return PhotonOutcome(s.bins + kScatterCapped, s.max_scatterings, w);
}

uint fixed_weight(float w) { return uint(w * 1048576.0 + 0.5); }  // 2^20, as scatter_math.h

// Ray casting pieces: the GLSL twin of engine/kernels/volume_sample.h (trilinear sampling, the
// clipping plane, gradient shading; the slab test is in slab.glsl) and of volume_transfer.h's
// transfer function. The including kernel defines `float volume_at(uint index)`,
// `vec4 tf_at(uint entry)`, the constant `bool VOLUME_QUADS` and `vec4 volume_quad_at(uint index)`
// (raymarch_quads.comp's texels). No loops: raymarch calls these inside its sample loop (see
// slab.glsl).

// The eight corners' indices as one base index plus offsets: lavapipe multiplies each lane's
// 32-bit integers with a slow vector instruction, so a sample multiplies twice, not sixteen times.
// With VOLUME_QUADS, the corners come four to a texel from volume_quad_at (raymarch_quads.comp),
// in the same order and arithmetic.
float trilinear(vec3 u, uvec3 dims) {
  const vec3 c = clamp(u, vec3(0.0), vec3(dims - 1u));
  const vec3 fl = floor(c);
  const uvec3 i0 = uvec3(fl);
  const uvec3 up = min(i0 + 1u, dims - 1u) - i0;  // 0 on the last voxel of an axis
  const uint row = dims.x, slice = dims.x * dims.y;
  const uint b = (i0.z * dims.y + i0.y) * dims.x + i0.x;
  const uint x1 = up.x, y1 = up.y != 0u ? row : 0u, z1 = up.z != 0u ? slice : 0u;
  const vec3 f = c - fl;
  if (VOLUME_QUADS) {
    const vec4 q0 = volume_quad_at(b), q1 = volume_quad_at(b + z1);
    const float c00 = q0.x * (1.0 - f.x) + q0.y * f.x;
    const float c10 = q0.z * (1.0 - f.x) + q0.w * f.x;
    const float c01 = q1.x * (1.0 - f.x) + q1.y * f.x;
    const float c11 = q1.z * (1.0 - f.x) + q1.w * f.x;
    const float c0 = c00 * (1.0 - f.y) + c10 * f.y;
    const float c1 = c01 * (1.0 - f.y) + c11 * f.y;
    return c0 * (1.0 - f.z) + c1 * f.z;
  }
  const float c00 = volume_at(b) * (1.0 - f.x) + volume_at(b + x1) * f.x;
  const float c10 = volume_at(b + y1) * (1.0 - f.x) + volume_at(b + y1 + x1) * f.x;
  const float c01 = volume_at(b + z1) * (1.0 - f.x) + volume_at(b + z1 + x1) * f.x;
  const float c11 = volume_at(b + z1 + y1) * (1.0 - f.x) + volume_at(b + z1 + y1 + x1) * f.x;
  const float c0 = c00 * (1.0 - f.y) + c10 * f.y;
  const float c1 = c01 * (1.0 - f.y) + c11 * f.y;
  return c0 * (1.0 - f.z) + c1 * f.z;
}

vec4 transfer(float v, uint size) {
  const float x = clamp(v, 0.0, 1.0) * float(size - 1u);
  uint k = uint(x);
  if (k > size - 2u) k = size - 2u;
  const float w = x - float(k);
  const vec4 a = tf_at(k), b = tf_at(k + 1u);
  return a + (b - a) * w;
}

// The twin of volume::clip_span: keep the part of [t_near, t_far] at or above (keep_above) or at
// or below `plane` on `axis`.
bool clip_span(vec3 o, vec3 d, uint axis, float plane, bool keep_above, inout float t_near,
               inout float t_far) {
  const float oa = o[axis], da = d[axis];
  if (da == 0.0) return keep_above ? oa >= plane : oa <= plane;
  const float t = (plane - oa) / da;
  if ((da > 0.0) == keep_above) {
    if (t > t_near) t_near = t;
  } else if (t < t_far) {
    t_far = t;
  }
  return t_near < t_far;
}

// The twin of volume::octahedral.
vec3 octahedral(uint bits) {
  vec2 e = unpackSnorm2x16(bits);
  const float z = 1.0 - abs(e.x) - abs(e.y);
  if (z < 0.0) {
    e = vec2((1.0 - abs(e.y)) * (e.x < 0.0 ? -1.0 : 1.0),
             (1.0 - abs(e.x)) * (e.y < 0.0 ? -1.0 : 1.0));
  }
  return normalize(vec3(e, z));
}

// The twin of volume::Lighting and volume::lighting.
struct Lighting {
  vec3 l, h;
  float ambient, diffuse, specular, shininess;
};

Lighting lighting(vec3 dir, bool headlight, uint light_bits, uint ambient_diffuse, uint specular) {
  Lighting L;
  const vec3 v = -dir;
  L.l = v;
  L.h = v;
  if (!headlight) {
    L.l = octahedral(light_bits);
    const vec3 s = L.l + v;
    const float len = length(s);
    L.h = len > 1e-6 ? s * (1.0 / len) : L.l;
  }
  const vec2 ad = unpackUnorm2x16(ambient_diffuse), ss = unpackUnorm2x16(specular);
  L.ambient = ad.x;
  L.diffuse = ad.y;
  L.specular = ss.x;
  L.shininess = ss.y * float(kRayMaxShininess);
  return L;
}

// The twin of volume::central_gradient, as six trilinear lookups everywhere: the shared body's
// path for a cell well inside the volume reads the same field (32 voxels, once), but lavapipe
// runs both sides of a branch, and the two paths together cost it more than six lookups alone.
vec3 central_gradient(vec3 u, uvec3 dims) {
  const vec3 X = vec3(1.0, 0.0, 0.0), Y = vec3(0.0, 1.0, 0.0), Z = vec3(0.0, 0.0, 1.0);
  return vec3(trilinear(u + X, dims) - trilinear(u - X, dims),
              trilinear(u + Y, dims) - trilinear(u - Y, dims),
              trilinear(u + Z, dims) - trilinear(u - Z, dims));
}

// The twin of volume::shade_at: Blinn-Phong from the central-difference gradient.
vec4 shade_at(vec4 col, vec3 u, uvec3 dims, vec3 spacing, float value_scale, Lighting L) {
  const vec3 g = central_gradient(u, dims);
  const float gx = g.x, gy = g.y, gz = g.z;
  const float largest = max(abs(gx), max(abs(gy), abs(gz)));
  if (largest * abs(value_scale) < 2e-4) return col;
  vec3 n = normalize(vec3(gx, gy, gz) / spacing);
  float ndl = dot(n, L.l);
  if (ndl < 0.0) {
    n = -n;
    ndl = -ndl;
  }
  const float ndh = max(dot(n, L.h), 0.0);
  const float lit = L.ambient + L.diffuse * ndl;
  const float spec = ndh > 0.0 ? L.specular * pow(ndh, L.shininess) : 0.0;
  return vec4(col.rgb * lit + spec, col.a);
}

// Ray casting pieces: the GLSL twin of engine/kernels/volume_math.h (trilinear sampling,
// transfer function, the clipping plane, gradient shading; the slab test is in slab.glsl). The
// including kernel defines `float volume_at(uint index)` and `vec4 tf_at(uint entry)`. No loops:
// raymarch calls these inside its sample loop (see slab.glsl).
float voxel(uvec3 i, uvec3 dims) { return volume_at((i.z * dims.y + i.y) * dims.x + i.x); }

float trilinear(vec3 u, uvec3 dims) {
  const vec3 c = clamp(u, vec3(0.0), vec3(dims - 1u));
  const vec3 fl = floor(c);
  const uvec3 i0 = uvec3(fl);
  const uvec3 i1 = min(i0 + 1u, dims - 1u);
  const vec3 f = c - fl;
  const float c00 = voxel(uvec3(i0.x, i0.y, i0.z), dims) * (1.0 - f.x) + voxel(uvec3(i1.x, i0.y, i0.z), dims) * f.x;
  const float c10 = voxel(uvec3(i0.x, i1.y, i0.z), dims) * (1.0 - f.x) + voxel(uvec3(i1.x, i1.y, i0.z), dims) * f.x;
  const float c01 = voxel(uvec3(i0.x, i0.y, i1.z), dims) * (1.0 - f.x) + voxel(uvec3(i1.x, i0.y, i1.z), dims) * f.x;
  const float c11 = voxel(uvec3(i0.x, i1.y, i1.z), dims) * (1.0 - f.x) + voxel(uvec3(i1.x, i1.y, i1.z), dims) * f.x;
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

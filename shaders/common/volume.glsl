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

// One edge of volume::central_gradient's shared-cell path: the difference along `axis` (a unit
// step in voxels) on the cell edge through corner e, whose corners c0 (at e) and c1 (one step on)
// the caller read; w the cell weights along the axis.
float edge_difference(uvec3 e, uvec3 axis, float c0, float c1, vec2 w, uvec3 dims) {
  return w.x * (c1 - voxel(e - axis, dims)) + w.y * (voxel(e + 2u * axis, dims) - c0);
}

// The twin of volume::central_gradient, unrolled (no loop: raymarch calls it in its sample loop).
vec3 central_gradient(vec3 u, uvec3 dims) {
  if (!(all(greaterThanEqual(u, vec3(1.0))) && all(lessThan(u, vec3(dims - 2u))))) {
    return vec3(trilinear(u + vec3(1.0, 0.0, 0.0), dims) - trilinear(u - vec3(1.0, 0.0, 0.0), dims),
                trilinear(u + vec3(0.0, 1.0, 0.0), dims) - trilinear(u - vec3(0.0, 1.0, 0.0), dims),
                trilinear(u + vec3(0.0, 0.0, 1.0), dims) - trilinear(u - vec3(0.0, 0.0, 1.0), dims));
  }
  const uvec3 i = uvec3(u);  // u >= 1: the floor
  const vec3 f = u - vec3(i);
  const vec2 wx = vec2(1.0 - f.x, f.x), wy = vec2(1.0 - f.y, f.y), wz = vec2(1.0 - f.z, f.z);
  const uvec3 X = uvec3(1u, 0u, 0u), Y = uvec3(0u, 1u, 0u), Z = uvec3(0u, 0u, 1u);
  // The cell's corners, cZYX = voxel(i + (X, Y, Z)).
  const float c000 = voxel(i, dims), c001 = voxel(i + X, dims);
  const float c010 = voxel(i + Y, dims), c011 = voxel(i + X + Y, dims);
  const float c100 = voxel(i + Z, dims), c101 = voxel(i + X + Z, dims);
  const float c110 = voxel(i + Y + Z, dims), c111 = voxel(i + X + Y + Z, dims);
  const float gx = wy.x * wz.x * edge_difference(i, X, c000, c001, wx, dims) +
                   wy.y * wz.x * edge_difference(i + Y, X, c010, c011, wx, dims) +
                   wy.x * wz.y * edge_difference(i + Z, X, c100, c101, wx, dims) +
                   wy.y * wz.y * edge_difference(i + Y + Z, X, c110, c111, wx, dims);
  const float gy = wx.x * wz.x * edge_difference(i, Y, c000, c010, wy, dims) +
                   wx.y * wz.x * edge_difference(i + X, Y, c001, c011, wy, dims) +
                   wx.x * wz.y * edge_difference(i + Z, Y, c100, c110, wy, dims) +
                   wx.y * wz.y * edge_difference(i + X + Z, Y, c101, c111, wy, dims);
  const float gz = wx.x * wy.x * edge_difference(i, Z, c000, c100, wz, dims) +
                   wx.y * wy.x * edge_difference(i + X, Z, c001, c101, wz, dims) +
                   wx.x * wy.y * edge_difference(i + Y, Z, c010, c110, wz, dims) +
                   wx.y * wy.y * edge_difference(i + X + Y, Z, c011, c111, wz, dims);
  return vec3(gx, gy, gz);
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

// Ray casting pieces: the GLSL twin of engine/kernels/volume_math.h (trilinear sampling,
// transfer function; the slab test is in slab.glsl). The including kernel declares
// `volume_data[]` and `tf[]`.
float voxel(uvec3 i, uvec3 dims) { return volume_data[(i.z * dims.y + i.y) * dims.x + i.x]; }

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
  const vec4 a = tf[k], b = tf[k + 1u];
  return a + (b - a) * w;
}

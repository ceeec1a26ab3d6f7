// Nebula lighting: the GLSL twin of engine/kernels/nebula_math.h (see there for the two
// discretisations of the optical-depth path integral and their errors). Needs slab.glsl and
// grid_cell.glsl; the including kernel defines `float density_at(uint cell)`, and with NEBULA_TABLE defined
// `float table_at(uint index)` for nebula_phase().
const float NEBULA_PI = 3.14159265358979323846;

struct NebulaGrid {
  vec3 origin;
  float cell;
  uvec3 dims;
};

int nebula_cell_of(NebulaGrid g, vec3 x, int ax) {
  const float f = floor((x[ax] - g.origin[ax]) / g.cell);
  return f <= 0.0 ? 0 : (f >= float(g.dims[ax] - 1u) ? int(g.dims[ax] - 1u) : int(f));
}

uint nebula_id(NebulaGrid g, ivec3 c) { return grid_cell_id(uvec3(c), g.dims); }

float path_integral(NebulaGrid g, vec3 a, vec3 b, uint mode, float step_len) {
  const vec3 d = b - a;
  const float len = length(d);
  if (!(len > 0.0)) return 0.0;
  const vec3 dir = d * (1.0 / len);
  const vec3 hi = g.origin + vec3(g.dims) * g.cell;
  float t0 = 0.0, t1 = len;
  if (!slab(a, dir, g.origin, hi, t0, t1)) return 0.0;
  float sum = 0.0;
  if (mode == OpticalPath_midpoint) {
    uint n = uint(ceil((t1 - t0) / step_len));
    n = n < 1u ? 1u : (n > kMaxPathSteps ? kMaxPathSteps : n);
    const float h = (t1 - t0) / float(n);
    for (uint i = 0u; i < n; ++i) {
      LOOP_TICK();
      const vec3 q = a + dir * (t0 + (float(i) + 0.5) * h);
      const ivec3 c = ivec3(nebula_cell_of(g, q, 0), nebula_cell_of(g, q, 1), nebula_cell_of(g, q, 2));
      sum += density_at(nebula_id(g, c)) * h;
    }
    return sum;
  }
  const vec3 p0 = a + dir * t0;
  ivec3 c = ivec3(nebula_cell_of(g, p0, 0), nebula_cell_of(g, p0, 1), nebula_cell_of(g, p0, 2));
  ivec3 stepc;
  vec3 tnext, tdelta;
  for (int ax = 0; ax < 3; ++ax) {
    LOOP_TICK();
    const float da = dir[ax];
    stepc[ax] = da > 0.0 ? 1 : (da < 0.0 ? -1 : 0);
    if (stepc[ax] == 0) {
      tnext[ax] = VOLUME_FAR;
      tdelta[ax] = VOLUME_FAR;
    } else {
      const float face = g.origin[ax] + float(c[ax] + (stepc[ax] > 0 ? 1 : 0)) * g.cell;
      tnext[ax] = (face - a[ax]) / da;
      tdelta[ax] = g.cell / abs(da);
    }
  }
  float t = t0;
  const uint max_pieces = g.dims.x + g.dims.y + g.dims.z + 3u;
  for (uint it = 0u; it < max_pieces; ++it) {
    LOOP_TICK();
    const int ax = tnext.x < tnext.y ? (tnext.x < tnext.z ? 0 : 2) : (tnext.y < tnext.z ? 1 : 2);
    const float tn = min(tnext[ax], t1);
    if (tn > t) sum += density_at(nebula_id(g, c)) * (tn - t);
    if (tnext[ax] >= t1) break;
    t = tn;
    c[ax] += stepc[ax];
    if (c[ax] < 0 || c[ax] >= int(g.dims[ax])) break;
    tnext[ax] += tdelta[ax];
  }
  return sum;
}

#ifdef NEBULA_TABLE
float nebula_phase(uint rows, uint bins, float tau_step, float tau, float mu) {
  const float fr = clamp(tau / tau_step, 0.0, float(rows - 1u));
  const uint r0 = uint(fr), r1 = r0 + 1u < rows ? r0 + 1u : r0;
  const float wr = fr - float(r0);
  const float fb = clamp((mu + 1.0) * float(bins) * 0.5 - 0.5, 0.0, float(bins - 1u));
  const uint b0 = uint(fb), b1 = b0 + 1u < bins ? b0 + 1u : b0;
  const float wb = fb - float(b0);
  const float v0 = table_at(r0 * bins + b0) * (1.0 - wb) + table_at(r0 * bins + b1) * wb;
  const float v1 = table_at(r1 * bins + b0) * (1.0 - wb) + table_at(r1 * bins + b1) * wb;
  return (v0 * (1.0 - wr) + v1 * wr) / (2.0 * NEBULA_PI * (2.0 / float(bins)));
}
#endif

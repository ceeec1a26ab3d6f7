#version 450
#extension GL_GOOGLE_include_directive : require
// raymarch: one pixel per invocation; the GLSL twin of volume::raymarch_pixel
// (engine/kernels/volume_math.h: segments, midpoint samples, opacity correction, early ray
// termination, empty-space skipping, the thesis's lerp mode).
#include "kernel_base.glsl"
#include "slab.glsl"
#include "engine/kernels/atom_params.h"

layout(std430, binding = 1) readonly buffer Volume { float volume_data[]; };
layout(std430, binding = 2) readonly buffer Tf { vec4 tf[]; };
layout(std430, binding = 3) readonly buffer Bricks { vec4 bricks[]; };
layout(std430, binding = 4) writeonly buffer Image { vec4 image[]; };
MASAV_PUSH(RaymarchLayout);

#include "volume.glsl"

void brick_bounds(int a, uint b, uint nb, vec3 spacing, out float lo, out float hi) {
  const uint brick = p.brick;
  lo = b == 0u ? p.box_min[a] : p.box_min[a] + (float(b * brick) + 0.5) * spacing[a];
  hi = b + 1u == nb ? p.box_max[a] : p.box_min[a] + (float((b + 1u) * brick) + 0.5) * spacing[a];
}

vec4 march(uint px, uint py) {
  vec4 acc = vec4(0.0);
  const uint width = p.width, height = p.height, brick = p.brick;
  const bool lerp_mode = p.mode == Compositing_lerp;
  const bool skip = p.skip_empty != 0u && !lerp_mode;
  const vec3 eye = p.eye;
  const float nx = (float(px) + 0.5) / float(width) * 2.0 - 1.0;
  const float ny = 1.0 - (float(py) + 0.5) / float(height) * 2.0;
  const vec3 dir = normalize(p.forward + p.right * nx + p.up * ny);
  const vec3 lo = p.box_min, hi = p.box_max;
  float tn = 0.0, tfar = VOLUME_FAR;
  if (!slab(eye, dir, lo, hi, tn, tfar)) return acc;
  const float step_len = p.step, len = tfar - tn;
  const uint n = uint(ceil(len / step_len));
  const uvec3 dims = p.dims;
  const vec3 spacing = (hi - lo) / vec3(dims);
  const uvec3 nb = (dims + brick - 1u) / brick;
  // No loop may nest in this one (see slab.glsl): lavapipe would count each sample twice.
  uint i = 0u;
  bool done = false;
  for (uint it = 0u; it < n; ++it) {
    if (i >= n || done) break;
    LOOP_TICK();
    const uint seg = lerp_mode ? n - 1u - i : i;
    const float s0 = tn + float(seg) * step_len;
    const float s1 = min(s0 + step_len, tfar);
    const float tm = 0.5 * (s0 + s1);
    const vec3 pos = eye + dir * tm;
    const vec3 u = (pos - lo) / spacing - 0.5;
    bool skipped = false;
    if (skip) {
      const uvec3 bi = uvec3(clamp(floor(u / float(brick)), vec3(0.0), vec3(nb - 1u)));
      if (bricks[(bi.z * nb.y + bi.y) * nb.x + bi.x].z <= 0.0) {
        vec3 blo, bhi;
        brick_bounds(0, bi.x, nb.x, spacing, blo.x, bhi.x);
        brick_bounds(1, bi.y, nb.y, spacing, blo.y, bhi.y);
        brick_bounds(2, bi.z, nb.z, spacing, blo.z, bhi.z);
        float t0 = tm, t1 = VOLUME_FAR;
        uint next = i + 1u;
        if (slab(eye, dir, blo, bhi, t0, t1)) {
          const float first = ceil((t1 - tn) / step_len - 0.5);
          if (first > float(next)) next = first >= float(n) ? n : uint(first);
        }
        i = next;
        skipped = true;
      }
    }
    if (!skipped) {
      const float v = trilinear(u, dims);
      const vec4 col = transfer((v - p.value_min) * p.value_scale, p.tf_size);
      if (lerp_mode) {
        acc.rgb += (col.rgb - acc.rgb) * col.a;
        acc.a += (1.0 - acc.a) * col.a;
      } else {
        const float h = s1 - s0;
        const float alpha = 1.0 - pow(max(0.0, 1.0 - col.a), h / p.reference_step);
        const float w = (1.0 - acc.a) * alpha;
        acc.rgb += w * col.rgb;
        acc.a += w;
        done = acc.a >= p.termination_alpha;
      }
      ++i;
    }
  }
  return acc;
}

void run() {
  const uint id = flat_invocation_id();
  const uint width = p.width;
  if (id >= width * p.height) return;
  image[id] = march(id % width, id / width);
}

void main() {
  run();
  report_loop_ticks();
}

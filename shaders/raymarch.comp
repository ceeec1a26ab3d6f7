#version 450
#extension GL_GOOGLE_include_directive : require
// raymarch: one pixel per invocation; the GLSL twin of volume::raymarch_pixel
// (engine/kernels/volume_math.h: segments, midpoint samples, opacity correction, early ray
// termination, empty-space skipping, the thesis's lerp mode).
#include "kernel_base.glsl"
#include "slab.glsl"

layout(std430, binding = 1) readonly buffer Volume { float volume_data[]; };
layout(std430, binding = 2) readonly buffer Tf { vec4 tf[]; };
layout(std430, binding = 3) readonly buffer Bricks { vec4 bricks[]; };
layout(std430, binding = 4) writeonly buffer Image { vec4 image[]; };
layout(push_constant) uniform Push {
  vec4 eye_step;
  vec4 forward_ref;
  vec4 right_term;
  vec4 up_vmin;
  vec4 box_min_vscale;
  vec4 box_max;
  uvec4 dims_tf;
  uvec4 wh_brick_flags;  // width, height, brick, flags (1: lerp, 2: skip empty)
} pc;

#include "volume.glsl"

void brick_bounds(int a, uint b, uint nb, vec3 spacing, out float lo, out float hi) {
  const uint brick = pc.wh_brick_flags.z;
  lo = b == 0u ? pc.box_min_vscale[a] : pc.box_min_vscale[a] + (float(b * brick) + 0.5) * spacing[a];
  hi = b + 1u == nb ? pc.box_max[a] : pc.box_min_vscale[a] + (float((b + 1u) * brick) + 0.5) * spacing[a];
}

vec4 march(uint px, uint py) {
  vec4 acc = vec4(0.0);
  const uint width = pc.wh_brick_flags.x, height = pc.wh_brick_flags.y, brick = pc.wh_brick_flags.z;
  const bool lerp_mode = (pc.wh_brick_flags.w & 1u) != 0u;
  const bool skip = (pc.wh_brick_flags.w & 2u) != 0u && !lerp_mode;
  const vec3 eye = pc.eye_step.xyz;
  const float nx = (float(px) + 0.5) / float(width) * 2.0 - 1.0;
  const float ny = 1.0 - (float(py) + 0.5) / float(height) * 2.0;
  const vec3 dir = normalize(pc.forward_ref.xyz + pc.right_term.xyz * nx + pc.up_vmin.xyz * ny);
  const vec3 lo = pc.box_min_vscale.xyz, hi = pc.box_max.xyz;
  float tn = 0.0, tfar = VOLUME_FAR;
  if (!slab(eye, dir, lo, hi, tn, tfar)) return acc;
  const float step_len = pc.eye_step.w, len = tfar - tn;
  const uint n = uint(ceil(len / step_len));
  const uvec3 dims = pc.dims_tf.xyz;
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
      const vec4 col = transfer((v - pc.up_vmin.w) * pc.box_min_vscale.w, pc.dims_tf.w);
      if (lerp_mode) {
        acc.rgb += (col.rgb - acc.rgb) * col.a;
        acc.a += (1.0 - acc.a) * col.a;
      } else {
        const float h = s1 - s0;
        const float alpha = 1.0 - pow(max(0.0, 1.0 - col.a), h / pc.forward_ref.w);
        const float w = (1.0 - acc.a) * alpha;
        acc.rgb += w * col.rgb;
        acc.a += w;
        done = acc.a >= pc.right_term.w;
      }
      ++i;
    }
  }
  return acc;
}

void run() {
  const uint id = flat_invocation_id();
  const uint width = pc.wh_brick_flags.x;
  if (id >= width * pc.wh_brick_flags.y) return;
  image[id] = march(id % width, id / width);
}

void main() {
  run();
  report_loop_ticks();
}

#version 450
#extension GL_GOOGLE_include_directive : require
// raymarch: one pixel per invocation, in 8x8 tiles; the GLSL twin of volume::raymarch_pixel
// (engine/kernels/volume_math.h: segments, midpoint samples, opacity correction, early ray
// termination, empty space skipped per segment in cubes of bricks of one kind, the thesis's lerp
// mode).
#include "kernel_base.glsl"
#include "slab.glsl"
#include "engine/kernels/atom_params.h"

// What the kernel only reads are uniform texel buffers (compute/vk_kernels.cpp: lavapipe fetches a
// texel with a gather, where it loads a storage buffer's element in a loop over the lanes).
layout(binding = 1) uniform samplerBuffer volume_texels;      // r32f
layout(binding = 2) uniform samplerBuffer tf_texels;          // rgba32f
layout(binding = 3) uniform samplerBuffer brick_texels;       // rgba32f
layout(std430, binding = 4) writeonly buffer Image { vec4 image[]; };
layout(binding = 5) uniform samplerBuffer tf_integral_texels;  // rgba32f
layout(binding = 6) uniform samplerBuffer quad_texels;  // rgba32f: raymarch_quads' output
MASAV_PUSH(RaymarchLayout);
float volume_at(uint index) { return texelFetch(volume_texels, int(index)).r; }
vec4 tf_at(uint entry) { return texelFetch(tf_texels, int(entry)); }
vec4 tf_integral_at(uint index) { return texelFetch(tf_integral_texels, int(index)); }
// bits & kRayModeFlags, as a constant: the paths a pipeline does not take compile out (lavapipe
// would otherwise run each branch that no lane takes, its loads included).
layout(constant_id = kSpecRayModes) const uint RAY_MODES = 0u;
bool ray_mode(uint flag) { return (RAY_MODES & flag) != 0u; }
// The brick size (bits >> kRayBrickShift & 31), as a constant: the brick of a sample is then a
// shift or a multiplication, where lavapipe divided each lane's three coordinates one by one.
layout(constant_id = kSpecRayBrick) const uint RAY_BRICK = 4u;
// The form of x^(step / reference_step) (kRayPow*: volume::pow_step_form, on the host), as a
// constant: lavapipe would otherwise compute all five forms, pow's logarithm and exponential
// included, for every sample.
layout(constant_id = kSpecRayPow) const uint RAY_POW = 0u;
// Whether the trilinear corners come four to a texel from quad_texels (compute/vk_volume.cpp).
layout(constant_id = kSpecVolumeQuads) const bool VOLUME_QUADS = false;
vec4 volume_quad_at(uint index) { return texelFetch(quad_texels, int(index)); }

#include "volume.glsl"
#include "preintegration.glsl"

// The twins of volume::ray_width and its neighbours: RaymarchLayout's packed small integers.
uint ray_width() { return p.image_size & 0xffffu; }
uint ray_height() { return p.image_size >> 16; }
uint ray_brick() { return RAY_BRICK; }
uint ray_tf_size() { return (p.bits >> kRayTfSizeShift) & 8191u; }

// The ray's span clipped by the plane, where kRayClip asks for it (volume::voxel_ray).
bool clip_ray(vec3 eye, vec3 dir, inout float tn, inout float tfar) {
  if (!ray_mode(kRayClip)) return true;
  return clip_span(eye, dir, (p.bits >> kRayClipAxisShift) & 3u, p.clip_position,
                   (p.bits & kRayClipKeepAbove) != 0u, tn, tfar);
}

Lighting ray_lighting(vec3 dir) {
  return lighting(dir, (p.bits & kRayHeadlight) != 0u, p.shade_light, p.shade_ambient_diffuse,
                  p.shade_specular);
}

// The GLSL twin of volume::box_exit: where the ray u(t) = u0 + du t leaves the cells lo .. hi of
// `count` cells of `size` voxels on one axis (the outermost cells reach to infinity outward).
float axis_exit(float u0, float du, float inv_du, uint lo, uint hi, uint count, float size,
                float exit) {
  float face = -1.0;
  if (du > 0.0 && hi + 1u < count) face = float(hi + 1u) * size;
  if (du < 0.0 && lo > 0u) face = float(lo) * size;
  return face >= 0.0 ? min(exit, (face - u0) * inv_du) : exit;
}

// The twin of volume::skip_span's exit: brick bi's lookup b = (min, max, alpha, stride) holds for
// every brick within stride - 1 of bi; where the ray leaves that cube of bricks.
float skip_exit(vec3 u0, vec3 du, vec3 inv_du, uvec3 bi, vec4 b, uvec3 nb, float size) {
  const uint reach = b.w >= 2.0 && b.w <= float(kBrickSkipMaxRadius + 1u) ? uint(b.w) - 1u : 0u;
  const uvec3 lo = uvec3(max(ivec3(bi) - int(reach), ivec3(0)));
  const uvec3 hi = min(bi + reach, nb - 1u);
  float exit = VOLUME_FAR;
  exit = axis_exit(u0.x, du.x, inv_du.x, lo.x, hi.x, nb.x, size, exit);
  exit = axis_exit(u0.y, du.y, inv_du.y, lo.y, hi.y, nb.y, size, exit);
  return axis_exit(u0.z, du.z, inv_du.z, lo.z, hi.z, nb.z, size, exit);
}

// The twins of volume::pow_step_form, volume::pow_in_form and volume::pow_step: x^e, with a
// square root or product for e = 1/4, 1/2, 1, 2.
uint pow_step_form(float e) {
  if (e == 1.0) return kRayPowOne;
  if (e == 0.5) return kRayPowHalf;
  if (e == 0.25) return kRayPowQuarter;
  if (e == 2.0) return kRayPowTwo;
  return kRayPowGeneral;
}
float pow_in_form(float x, float e, uint form) {
  if (form == kRayPowOne) return x;
  if (form == kRayPowHalf) return sqrt(x);
  if (form == kRayPowQuarter) return sqrt(sqrt(x));
  if (form == kRayPowTwo) return x * x;
  return pow(x, e);
}
float pow_step(float x, float e) { return pow_in_form(x, e, pow_step_form(e)); }

// The twin of volume::first_segment_after (inv_step = 1 / step).
uint first_segment_after(float t, float tn, float inv_step, uint i, uint n) {
  uint next = i + 1u;
  const float x = (t - tn) * inv_step - 0.5;  // the ceiling of x is the segment
  if (x > float(next)) {
    const uint k = uint(x);
    next = x >= float(n) ? n : (float(k) < x ? k + 1u : k);
  }
  return next;
}

// The twin of volume::skip_span's brick index: floor(u / brick) as floor(u) / brick, a shift
// (brick_shift != 0) for a power of two.
uvec3 brick_of(vec3 u, uint brick_shift, uvec3 nb) {
  const uvec3 v = uvec3(max(u, vec3(0.0)));
  return min(brick_shift != 0u ? v >> brick_shift : v / ray_brick(), nb - 1u);
}

// The twin of volume::voxel_ray's brick_shift: log2 of the brick where that is a power of two,
// else 0.
uint brick_shift() {
  const uint b = ray_brick();
  return (b & (b - 1u)) == 0u ? uint(findLSB(b)) : 0u;
}

vec4 march(uint px, uint py) {
  vec4 acc = vec4(0.0);
  const uint width = ray_width(), height = ray_height();
  const bool lerp_mode = ray_mode(kRayLerp);
  const bool skip = ray_mode(kRaySkipEmpty) && !lerp_mode;
  const bool shade = ray_mode(kRayShade);
  const vec3 eye = p.eye;
  const float nx = (float(px) + 0.5) / float(width) * 2.0 - 1.0;
  const float ny = 1.0 - (float(py) + 0.5) / float(height) * 2.0;
  const vec3 dir = normalize(p.forward + p.right * nx + p.up * ny);
  const vec3 lo = p.box_min, hi = p.box_max;
  float tn = 0.0, tfar = VOLUME_FAR;
  if (!slab(eye, dir, lo, hi, tn, tfar) || !clip_ray(eye, dir, tn, tfar)) return acc;
  const float step_len = p.step, len = tfar - tn;
  const uint n = uint(ceil(len / step_len));
  const uvec3 dims = p.dims;
  const vec3 spacing = (hi - lo) / vec3(dims);
  const vec3 u0 = (eye - lo) / spacing - 0.5;
  const vec3 du = dir / spacing;
  const vec3 inv_du = vec3(du.x != 0.0 ? 1.0 / du.x : 0.0, du.y != 0.0 ? 1.0 / du.y : 0.0,
                           du.z != 0.0 ? 1.0 / du.z : 0.0);
  const float brick = float(ray_brick());
  const uvec3 nb = (dims + ray_brick() - 1u) / ray_brick();
  Lighting light;
  if (shade) light = ray_lighting(dir);
  const uint shift = brick_shift();
  const float inv_step = 1.0 / step_len;
  const float exponent = step_len / p.reference_step;
  float occupied_until = -1.0;  // the ray is in an occupied brick for t < occupied_until
  // No loop may nest in this one (see slab.glsl): lavapipe would count each sample twice.
  uint i = 0u;
  bool done = false;
  // The last segment, shorter than a step, is composited after the loop (it is the last one
  // composited either way), so that the loop takes the full step's form of the power only.
  vec4 last = vec4(0.0);
  for (uint it = 0u; it < n; ++it) {
    if (i >= n || done) break;
    LOOP_TICK();
    const uint seg = lerp_mode ? n - 1u - i : i;
    const float s0 = tn + float(seg) * step_len;
    const float s1 = min(s0 + step_len, tfar);
    const float tm = 0.5 * (s0 + s1);
    const vec3 u = u0 + du * tm;
    bool skipped = false;
    if (skip && tm >= occupied_until) {
      const uvec3 bi = brick_of(u, shift, nb);
      const vec4 b = texelFetch(brick_texels, int((bi.z * nb.y + bi.y) * nb.x + bi.x));
      // One exit either way, empty or occupied (lanes that disagree run one, not two).
      const float exit = skip_exit(u0, du, inv_du, bi, b, nb, brick);
      if (b.z <= 0.0) {
        i = first_segment_after(exit, tn, inv_step, i, n);
        skipped = true;
      } else {
        occupied_until = exit;
      }
    }
    if (!skipped) {
      const float v = trilinear(u, dims);
      vec4 col = transfer((v - p.value_min) * p.value_scale, ray_tf_size());
      if (shade && col.a > 0.0) col = shade_at(col, u, dims, spacing, p.value_scale, light);
      if (lerp_mode) {
        acc.rgb += (col.rgb - acc.rgb) * col.a;
        acc.a += (1.0 - acc.a) * col.a;
      } else if (seg + 1u == n) {
        last = col;
      } else if (col.a > 0.0) {  // a transparent sample adds nothing: 1 - 1^e = 0
        // The dispatch's full-step exponent, in the form RAY_POW names (a constant).
        const float alpha = 1.0 - pow_in_form(max(0.0, 1.0 - col.a), exponent, RAY_POW);
        const float w = (1.0 - acc.a) * alpha;
        acc.rgb += w * col.rgb;
        acc.a += w;
        done = acc.a >= p.termination_alpha;
      }
      ++i;
    }
  }
  if (last.a > 0.0) {
    const float s0 = tn + float(n - 1u) * step_len;
    const float alpha =
        1.0 - pow_step(max(0.0, 1.0 - last.a), (min(s0 + step_len, tfar) - s0) / p.reference_step);
    const float w = (1.0 - acc.a) * alpha;
    acc.rgb += w * last.rgb;
    acc.a += w;
  }
  return acc;
}

uint last_boundary_before(float t, float tn, float inv_step, uint n) {
  const float q = (t - tn) * inv_step;
  return q >= float(n) ? n : (q > 0.0 ? uint(q) : 0u);
}

TfPos value_at(vec3 u0, vec3 du, float t, uvec3 dims) {
  return tf_pos((trilinear(u0 + du * t, dims) - p.value_min) * p.value_scale, ray_tf_size());
}

// The twin of volume::raymarch_pixel_preintegrated: the scalar at segment boundaries, each
// segment's colour and opacity from the pre-integrated table, runs of segments inside one
// cube of empty bricks skipped.
vec4 march_preintegrated(uint px, uint py) {
  vec4 acc = vec4(0.0);
  const bool skip = ray_mode(kRaySkipEmpty);
  const bool shade = ray_mode(kRayShade);
  const vec3 eye = p.eye;
  const float nx = (float(px) + 0.5) / float(ray_width()) * 2.0 - 1.0;
  const float ny = 1.0 - (float(py) + 0.5) / float(ray_height()) * 2.0;
  const vec3 dir = normalize(p.forward + p.right * nx + p.up * ny);
  const vec3 lo = p.box_min, hi = p.box_max;
  float tn = 0.0, tfar = VOLUME_FAR;
  if (!slab(eye, dir, lo, hi, tn, tfar) || !clip_ray(eye, dir, tn, tfar)) return acc;
  const float step_len = p.step, len = tfar - tn;
  const uint n = uint(ceil(len / step_len));
  const uvec3 dims = p.dims;
  const vec3 spacing = (hi - lo) / vec3(dims);
  const vec3 u0 = (eye - lo) / spacing - 0.5;
  const vec3 du = dir / spacing;
  const vec3 inv_du = vec3(du.x != 0.0 ? 1.0 / du.x : 0.0, du.y != 0.0 ? 1.0 / du.y : 0.0,
                           du.z != 0.0 ? 1.0 / du.z : 0.0);
  const float brick = float(ray_brick());
  const uvec3 nb = (dims + ray_brick() - 1u) / ray_brick();
  Lighting light;
  if (shade) light = ray_lighting(dir);
  const uint shift = brick_shift();
  const float inv_step = 1.0 / step_len;
  const float inv_ref = 1.0 / p.reference_step;
  float occupied_until = -1.0;  // the ray is in an occupied brick for t < occupied_until
  TfPos front = TfPos(0u, 0.0);
  bool have_front = false;  // front holds the value at boundary i
  // No loop may nest in this one (see slab.glsl). lavapipe runs the whole loop body in every
  // pass, whatever its lanes take, so a pass looks up one value: at the segment's start where
  // there is none yet (the ray's start, or just past a skip), else at its end, compositing the
  // segment. Every pass but the first moves i on, so n + 1 passes reach the end.
  uint i = 0u;
  bool done = false;
  for (uint it = 0u; it <= n; ++it) {
    if (i >= n || done) break;
    LOOP_TICK();
    if (skip && tn + float(i) * step_len >= occupied_until) {
      const vec3 u = u0 + du * (tn + float(i) * step_len);
      const uvec3 bi = brick_of(u, shift, nb);
      const vec4 b = texelFetch(brick_texels, int((bi.z * nb.y + bi.y) * nb.x + bi.x));
      const float exit = skip_exit(u0, du, inv_du, bi, b, nb, brick);
      float empty_until = -1.0;
      if (b.z <= 0.0) {
        empty_until = exit;
      } else {
        occupied_until = exit;
      }
      const uint j = empty_until >= 0.0 ? last_boundary_before(empty_until, tn, inv_step, n) : 0u;
      if (j > i) {  // segments i .. j-1 end inside the empty cell
        i = j;
        have_front = false;
      }
    }
    if (i < n) {
      const float s0 = tn + float(i) * step_len;
      const float s1 = min(s0 + step_len, tfar);
      const TfPos value = value_at(u0, du, have_front ? s1 : s0, dims);
      if (have_front) {
        const vec4 m = segment_mean(front, value);
        if (m.w > 0.0) {  // alpha = 1 - exp(-depth); colour = emission / depth per unit alpha
          const float alpha = 1.0 - exp(-m.w * (s1 - s0) * inv_ref);
          const float w = (1.0 - acc.a) * alpha;
          if (shade) {  // the segment's mean colour, lit at its midpoint
            const float inv = 1.0 / m.w;
            const vec4 col = shade_at(vec4(m.rgb * inv, m.w), u0 + du * (0.5 * (s0 + s1)), dims,
                                      spacing, p.value_scale, light);
            acc.rgb += w * col.rgb;
          } else {
            acc.rgb += (w / m.w) * m.rgb;
          }
          acc.a += w;
          done = acc.a >= p.termination_alpha;
        }
        ++i;
      }
      front = value;  // the value at boundary i
      have_front = true;
    }
  }
  return acc;
}

// Invocation id marches the pixel of volume::tile_pixel: 8x8 tiles, row-major.
void run() {
  const uint id = flat_invocation_id();
  const uint width = ray_width();
  const uint tiles_x = (width + 7u) / 8u;
  const uint tile = id / 64u, in_tile = id % 64u;
  const uint x = tile % tiles_x * 8u + in_tile % 8u, y = tile / tiles_x * 8u + in_tile / 8u;
  if (x >= width || y >= ray_height()) return;
  const bool preintegrated = ray_mode(kRayPreintegrate);
  image[y * width + x] = preintegrated ? march_preintegrated(x, y) : march(x, y);
}

void main() {
  MASAV_LOAD_PUSH();
  run();
  report_loop_ticks();
}

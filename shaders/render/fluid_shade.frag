#version 450
#extension GL_GOOGLE_include_directive : require
// Fluid surface, the last pass: the smoothed depth turned back into view-space points, normals from
// their neighbours (the side with the smaller depth step, so edges stay sharp), then water-like
// shading: the colour map's colour absorbed with thickness (Beer-Lambert: thin sheets let the
// scene behind show through, as refraction would), Fresnel reflection of a sky, a specular
// highlight. Writes the surface's depth so the box's edges in front of it stay in front.
#include "fluid_common.glsl"

layout(std430, set = 0, binding = 0) buffer Fluid { uint fluid[]; };
layout(push_constant) uniform Push {
  uvec4 shape;  // width, height
  vec4 proj;    // P[0][0], P[1][1], P[2][2], P[3][2] of the projection
  vec4 look;    // x: sphere radius (world), y: brightness
} pc;

layout(location = 0) out vec4 out_color;

uint plane() { return pc.shape.x * pc.shape.y; }

float smoothed(ivec2 p) {
  if (any(lessThan(p, ivec2(0))) || any(greaterThanEqual(p, ivec2(pc.shape.xy)))) return kEmpty;
  return uintBitsToFloat(fluid[kSmoothed * plane() + uint(p.y) * pc.shape.x + uint(p.x)]);
}

// The view-space point (camera looking down -z) at pixel p with view depth z.
vec3 view_point(ivec2 p, float z) {
  const vec2 ndc = (vec2(p) + 0.5) / vec2(pc.shape.xy) * 2.0 - 1.0;
  return vec3(ndc.x * z / pc.proj.x, ndc.y * z / pc.proj.y, -z);
}

vec3 neighbour_step(ivec2 p, vec3 c, ivec2 axis) {
  const float za = smoothed(p + axis), zb = smoothed(p - axis);
  const vec3 a = za < kEmpty ? view_point(p + axis, za) - c : vec3(1e30);
  const vec3 b = zb < kEmpty ? c - view_point(p - axis, zb) : vec3(1e30);
  if (za >= kEmpty && zb >= kEmpty) return vec3(0.0);
  return abs(a.z) < abs(b.z) ? a : b;
}

void main() {
  const ivec2 p = ivec2(gl_FragCoord.xy);
  const float z = smoothed(p);
  if (z >= kEmpty) discard;
  const uint i = uint(p.y) * pc.shape.x + uint(p.x);
  const vec3 c = view_point(p, z);
  const vec3 dx = neighbour_step(p, c, ivec2(1, 0));
  const vec3 dy = neighbour_step(p, c, ivec2(0, 1));
  vec3 n = cross(dx, dy);
  n = dot(n, n) > 0.0 ? normalize(n) : vec3(0.0, 0.0, 1.0);
  if (n.z < 0.0) n = -n;  // towards the camera
  const vec3 v = normalize(-c);
  const float weight = max(float(fluid[kWeight * plane() + i]), 1.0);
  const vec3 base = vec3(float(fluid[kRed * plane() + i]), float(fluid[kGreen * plane() + i]),
                         float(fluid[kBlue * plane() + i])) / weight * pc.look.y;
  const float thickness = float(fluid[kThickness * plane() + i]) / 256.0 * pc.look.x;
  const vec3 l = normalize(vec3(-0.4, 0.5, 0.75));
  const float diffuse = max(dot(n, l), 0.0);
  const float specular = pow(max(dot(n, normalize(l + v)), 0.0), 60.0);
  const float fresnel = 0.02 + 0.98 * pow(1.0 - max(dot(n, v), 0.0), 5.0);
  const vec3 r = reflect(-v, n);
  const vec3 sky = mix(vec3(0.05, 0.06, 0.09), vec3(0.55, 0.65, 0.8), clamp(r.y * 0.5 + 0.5, 0.0, 1.0));
  // Opacity from the thickness the view ray crosses: about one sphere diameter is half opaque.
  const float opacity = 1.0 - exp(-thickness / (3.0 * pc.look.x));
  const vec3 body = base * (0.3 + 0.7 * diffuse);
  const vec3 rgb = mix(body, sky, fresnel) + vec3(0.6 * specular);
  out_color = vec4(rgb, clamp(max(opacity, fresnel + specular), 0.0, 1.0));
  // Depth of the point: clip z / clip w with w = z.
  gl_FragDepth = clamp((pc.proj.z * c.z + pc.proj.w) / z, 0.0, 1.0);
}

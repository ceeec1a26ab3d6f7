#version 450
// Round sprites: opaque ones shaded as small spheres (depth cue), additive ones as soft glows.
layout(push_constant) uniform Push {
  mat4 view_proj;
  vec4 size;
  vec4 range;
  uvec4 mode;
  vec4 eye;
} pc;

layout(location = 0) in vec3 v_color;
layout(location = 1) flat in vec4 v_depth;  // clip z, w of the centre (and the nearest point)
layout(location = 0) out vec4 out_color;

void main() {
  if (v_depth.y <= 0.0) discard;  // behind the camera
  const vec2 d = gl_PointCoord * 2.0 - 1.0;
  const float r2 = dot(d, d);
  if (r2 > 1.0) discard;
  if (pc.range.z > 0.5) {
    out_color = vec4(v_color * exp(-3.0 * r2), 1.0);
  } else {
    const vec3 n = vec3(d.x, -d.y, sqrt(1.0 - r2));
    const float light = 0.35 + 0.65 * max(dot(n, normalize(vec3(-0.4, 0.5, 0.75))), 0.0);
    out_color = vec4(v_color * light, 1.0);
  }
}

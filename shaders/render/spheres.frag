#version 450
// Opaque points as lit sphere impostors: each sprite pixel is the visible point of a sphere of
// the sprite's radius, with its own depth (so intersecting spheres cut each other where real ones
// would) and a normal for diffuse and specular light from a lamp above and left of the camera.
layout(push_constant) uniform Push {
  mat4 view_proj;
  vec4 size;
  vec4 range;
  uvec4 mode;
  vec4 eye;
} pc;

layout(location = 0) in vec3 v_color;
// Clip z and w of the sphere's centre (xy) and of its point nearest the camera (zw).
layout(location = 1) flat in vec4 v_depth;
layout(location = 0) out vec4 out_color;

void main() {
  const vec2 d = gl_PointCoord * 2.0 - 1.0;
  const float r2 = dot(d, d);
  if (r2 > 1.0) discard;
  const float k = sqrt(1.0 - r2);
  // Clip coordinates are linear along the line from the centre to the nearest point.
  const vec2 zw = mix(v_depth.xy, v_depth.zw, k);
  gl_FragDepth = zw.x / zw.y;
  const vec3 n = vec3(d.x, -d.y, k);  // view space: x right, y up, z towards the camera
  const vec3 l = normalize(vec3(-0.4, 0.5, 0.75));
  const float diffuse = max(dot(n, l), 0.0);
  const float specular = pow(max(dot(n, normalize(l + vec3(0.0, 0.0, 1.0))), 0.0), 40.0);
  out_color = vec4(v_color * (0.22 + 0.78 * diffuse) + vec3(0.35 * specular), 1.0);
}

#version 450
// Box edges and axes: vertices (position, colour) pulled from a buffer.
struct LineVertex {
  vec4 position;
  vec4 color;
};
layout(std430, set = 0, binding = 0) readonly buffer Vertices { LineVertex vertices[]; };
layout(push_constant) uniform Push { mat4 view_proj; } pc;

layout(location = 0) out vec4 v_color;

void main() {
  const LineVertex v = vertices[gl_VertexIndex];
  gl_Position = pc.view_proj * vec4(v.position.xyz, 1.0);
  v_color = v.color;
}

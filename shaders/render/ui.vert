#version 450
// Dear ImGui's draw lists (the demo's panel and the text overlay): vertices and 16-bit indices
// pulled from buffers. ImDrawVert = pos (2 f32), uv (2 f32), colour (RGBA8): five words.
layout(std430, set = 0, binding = 0) readonly buffer Vertices { uint vwords[]; };
layout(std430, set = 0, binding = 1) readonly buffer Indices { uint iwords[]; };
layout(push_constant) uniform Push {
  vec4 transform;  // scale xy, translate zw: pixels to clip space
  uvec4 offsets;   // first index, first vertex, atlas width, atlas height
} pc;

layout(location = 0) out vec2 v_uv;
layout(location = 1) out vec4 v_color;

void main() {
  const uint k = pc.offsets.x + uint(gl_VertexIndex);
  const uint index = (iwords[k >> 1] >> ((k & 1u) * 16u)) & 0xFFFFu;
  const uint base = 5u * (pc.offsets.y + index);
  const vec2 pos = vec2(uintBitsToFloat(vwords[base]), uintBitsToFloat(vwords[base + 1u]));
  v_uv = vec2(uintBitsToFloat(vwords[base + 2u]), uintBitsToFloat(vwords[base + 3u]));
  v_color = unpackUnorm4x8(vwords[base + 4u]);
  gl_Position = vec4(pos * pc.transform.xy + pc.transform.zw, 0.0, 1.0);
}

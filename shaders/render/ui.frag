#version 450
// ImGui's font atlas (RGBA8, one u32 per texel) sampled bilinearly from a texel buffer.
layout(set = 0, binding = 2) uniform usamplerBuffer atlas;  // r32ui
layout(push_constant) uniform Push {
  vec4 transform;
  uvec4 offsets;
} pc;

layout(location = 0) in vec2 v_uv;
layout(location = 1) in vec4 v_color;
layout(location = 0) out vec4 out_color;

vec4 texel(ivec2 p) {
  const ivec2 size = ivec2(pc.offsets.zw);
  p = clamp(p, ivec2(0), size - 1);
  return unpackUnorm4x8(texelFetch(atlas, p.y * size.x + p.x).r);
}

void main() {
  const vec2 x = v_uv * vec2(pc.offsets.zw) - 0.5;
  const ivec2 i = ivec2(floor(x));
  const vec2 f = x - vec2(i);
  const vec4 t = mix(mix(texel(i), texel(i + ivec2(1, 0)), f.x),
                     mix(texel(i + ivec2(0, 1)), texel(i + ivec2(1, 1)), f.x), f.y);
  out_color = v_color * t;
}

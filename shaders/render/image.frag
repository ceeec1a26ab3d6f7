#version 450
// An image a compute kernel wrote into a buffer (row 0 at the top), bilinearly filtered:
// colour = gain * pixel^gamma. Formats: rgba8 (one u32 per pixel), rgba32f (four f32).
layout(std430, set = 0, binding = 0) readonly buffer Pixels { uint words[]; };
layout(push_constant) uniform Push {
  uvec4 shape;  // width, height, format (0 rgba8, 1 rgba32f), mono
  vec4 tone;    // gain, gamma, viewport width, viewport height
} pc;

layout(location = 0) in vec2 v_uv;
layout(location = 0) out vec4 out_color;

vec4 texel(ivec2 p) {
  p = clamp(p, ivec2(0), ivec2(pc.shape.xy) - 1);
  const uint i = uint(p.y) * pc.shape.x + uint(p.x);
  if (pc.shape.z == 0u) return unpackUnorm4x8(words[i]);
  return vec4(uintBitsToFloat(words[4u * i]), uintBitsToFloat(words[4u * i + 1u]),
              uintBitsToFloat(words[4u * i + 2u]), uintBitsToFloat(words[4u * i + 3u]));
}

void main() {
  vec4 c;
  if (vec2(pc.shape.xy) == pc.tone.zw) {
    c = texel(ivec2(gl_FragCoord.xy));  // one texel per pixel: no filtering needed
  } else {
    const vec2 x = v_uv * vec2(pc.shape.xy) - 0.5;
    const ivec2 i = ivec2(floor(x));
    const vec2 f = x - vec2(i);
    c = mix(mix(texel(i), texel(i + ivec2(1, 0)), f.x),
            mix(texel(i + ivec2(0, 1)), texel(i + ivec2(1, 1)), f.x), f.y);
  }
  vec3 rgb = pc.shape.w != 0u ? c.rrr : c.rgb;
  rgb = pc.tone.x * pow(max(rgb, vec3(0.0)), vec3(pc.tone.y));
  out_color = vec4(rgb, 1.0);
}

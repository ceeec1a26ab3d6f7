#version 450
// An image a compute kernel wrote into a buffer (row 0 at the top), bilinearly filtered:
// colour = gain * pixel^gamma. Formats: rgba8 (one u32 per pixel), rgba32f (four f32), read as
// texel buffers (render/renderer.cpp binds the image at the one of its format).
layout(set = 0, binding = 0) uniform usamplerBuffer pixels_rgba8;    // r32ui
layout(set = 0, binding = 1) uniform samplerBuffer pixels_rgba32f;   // rgba32f
layout(push_constant) uniform Push {
  uvec4 shape;  // width, height, format (0 rgba8, 1 rgba32f), mono
  vec4 tone;    // gain, gamma, viewport width, viewport height
} pc;

layout(location = 0) in vec2 v_uv;
layout(location = 0) out vec4 out_color;

// Both fetches stay in range (lavapipe runs both sides of the format's branch, and the binding
// of the other format holds the renderer's placeholder).
vec4 texel(ivec2 p) {
  p = clamp(p, ivec2(0), ivec2(pc.shape.xy) - 1);
  const int i = p.y * int(pc.shape.x) + p.x;
  if (pc.shape.z == 0u)
    return unpackUnorm4x8(texelFetch(pixels_rgba8, min(i, textureSize(pixels_rgba8) - 1)).r);
  return texelFetch(pixels_rgba32f, min(i, textureSize(pixels_rgba32f) - 1));
}

void main() {
  // One texel per pixel needs no filtering: its own texel at weights (0, 0), which mix returns
  // exactly. One set of four fetches either way (lavapipe would run both ways).
  const bool one_to_one = vec2(pc.shape.xy) == pc.tone.zw;
  const vec2 x = v_uv * vec2(pc.shape.xy) - 0.5;
  const ivec2 i = one_to_one ? ivec2(gl_FragCoord.xy) : ivec2(floor(x));
  const vec2 f = one_to_one ? vec2(0.0) : x - floor(x);
  const vec4 c = mix(mix(texel(i), texel(i + ivec2(1, 0)), f.x),
                     mix(texel(i + ivec2(0, 1)), texel(i + ivec2(1, 1)), f.x), f.y);
  vec3 rgb = pc.shape.w != 0u ? c.rrr : c.rgb;
  rgb = pc.tone.x * pow(max(rgb, vec3(0.0)), vec3(pc.tone.y));
  out_color = vec4(rgb, 1.0);
}

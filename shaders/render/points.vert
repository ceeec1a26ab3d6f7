#version 450
#extension GL_GOOGLE_include_directive : require
// Point sprites pulled straight from the compute backend's buffers: positions (vec4; w holds a
// per-point value) and an optional per-point scalar (u32 or f32) shown through a colour map.
#include "frame_common.glsl"

layout(std430, set = 0, binding = 0) readonly buffer Positions { vec4 positions[]; };
layout(std430, set = 0, binding = 1) readonly buffer Scalars { uint scalar_words[]; };
layout(std430, set = 0, binding = 2) readonly buffer Colormap { vec4 colormap[256]; };

layout(push_constant) uniform Push {
  mat4 view_proj;
  vec4 size;    // x: sprite diameter in px at reference depth, y: reference depth,
                // z: largest size the device draws, w: brightness
  vec4 range;   // x: scalar at the map's first colour, y: at its last, z: additive (1) or not
  uvec4 mode;   // x: 0 none, 1 u32 buffer, 2 f32 buffer, 3 position.w, 4 position.z,
                //    5 length of xyz of a vec4 buffer;
                // y: 1 = grey marker for points with position.w below uintBitsToFloat(z)
  vec4 eye;     // xyz: the camera; w: the sphere radius a sprite stands for (world units)
} pc;

layout(location = 0) out vec3 v_color;
// Clip z and w of the centre (xy) and of the sphere's point nearest the camera (zw).
layout(location = 1) flat out vec4 v_depth;

void main() {
  const vec4 p = positions[gl_VertexIndex];
  gl_Position = pc.view_proj * vec4(p.xyz, 1.0);
  const vec3 to_eye = normalize(pc.eye.xyz - p.xyz);
  v_depth = vec4(gl_Position.zw, (pc.view_proj * vec4(p.xyz + to_eye * pc.eye.w, 1.0)).zw);
  float s = 0.5 * (pc.range.x + pc.range.y);
  switch (pc.mode.x) {
    case 1u: s = float(scalar_words[gl_VertexIndex]); break;
    case 2u: s = uintBitsToFloat(scalar_words[gl_VertexIndex]); break;
    case 3u: s = p.w; break;
    case 4u: s = p.z; break;
    case 5u: {
      const uint b = 4u * uint(gl_VertexIndex);
      s = length(vec3(uintBitsToFloat(scalar_words[b]), uintBitsToFloat(scalar_words[b + 1u]),
                      uintBitsToFloat(scalar_words[b + 2u])));
      break;
    }
    default: break;
  }
  const float span = pc.range.y - pc.range.x;
  const float t = span != 0.0 ? (s - pc.range.x) / span : 0.5;
  v_color = COLORMAP_LOOKUP(colormap, t) * pc.size.w;
  if (pc.mode.y == 1u && p.w < uintBitsToFloat(pc.mode.z)) v_color = vec3(0.55) * pc.size.w;
  // Perspective: sprites shrink with depth, as the particles they stand for would.
  const float depth = max(gl_Position.w, 1e-4);
  gl_PointSize = clamp(pc.size.x * pc.size.y / depth, 1.0, pc.size.z);
}

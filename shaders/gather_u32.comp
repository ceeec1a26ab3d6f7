#version 450
#extension GL_GOOGLE_include_directive : require
// Gather of 32-bit elements (u32, i32, f32, fp32 reals).
#define ELEM_T uint
#include "gather.glsl"

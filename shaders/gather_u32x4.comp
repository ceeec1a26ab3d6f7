#version 450
#extension GL_GOOGLE_include_directive : require
// Gather of 16-byte elements (fp32 Real4: positions, velocities).
#define ELEM_T uvec4
#include "gather.glsl"

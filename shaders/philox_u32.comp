#version 450
#extension GL_GOOGLE_include_directive : require
// Philox4x32-10 words (common/philox_fill.glsl).
#define PHILOX_WORD(w) (w)
#include "philox_fill.glsl"

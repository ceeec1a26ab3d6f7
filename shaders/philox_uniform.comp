#version 450
#extension GL_GOOGLE_include_directive : require
// Philox4x32-10 words as uniform floats in [0, 1) (common/philox_fill.glsl).
#define PHILOX_WORD(w) floatBitsToUint(philox_u01(w))
#include "philox_fill.glsl"

// The fp32 SPH pair loops for any CPU (flags: engine/cpu/CMakeLists.txt).
#define MASAV_SIMD_NS simd_generic
#define MASAV_SIMD_KIND SphSimd::generic
#include "engine/cpu/cpu_sph_simd_body.inc"

// The fp32 SPH pair loops for avx2 (flags: engine/cpu/CMakeLists.txt).
#define MASAV_SIMD_NS simd_avx2
#define MASAV_SIMD_KIND SphSimd::avx2
#include "engine/cpu/cpu_sph_simd_body.inc"

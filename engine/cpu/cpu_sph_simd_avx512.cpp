// The fp32 SPH pair loops for avx512 (flags: engine/cpu/CMakeLists.txt).
#define MASAV_SIMD_NS simd_avx512
#define MASAV_SIMD_KIND SphSimd::avx512
#include "engine/cpu/cpu_sph_simd_body.inc"

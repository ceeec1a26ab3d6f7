#pragma once
// Shared pieces of the electron-cloud benchmarks: the thesis's Table 2.3 (states, particle
// counts, and its Quadro FX 5800 / Core2 Duo P8400 times) and small helpers.
#include <array>
#include <string>

#include "app/bench_common.h"
#include "engine/atom/orbital.h"

namespace masav::app {

struct ThesisRow {
  const char* state;
  uint32_t particles;
  double creation_s;   // "Electron Cloud Creation (sec)", CPU
  double color_cpu_s;  // "Color CPU (sec)"
  double color_gpu_s;  // "Color GPU (sec)"
};

// Thesis Table 2.3.
inline constexpr std::array<ThesisRow, 10> kThesisTable23 = {{
    {"state1", 630720, 4.1, 44.7, 0.288},
    {"state2", 483552, 3.6, 35.5, 0.227},
    {"state3", 316512, 3.2, 26.4, 0.164},
    {"state4", 1124640, 9.8, 67.4, 0.516},
    {"state5", 452016, 3.8, 34.3, 0.211},
    {"state6", 318528, 3.2, 24.8, 0.161},
    {"state7", 1123632, 10.3, 67.1, 0.499},
    {"state8", 165312, 1.9, 29.3, 0.126},
    {"state9", 132192, 1.5, 27.5, 0.105},
    {"state10", 1000001, 8.7, 64.1, 0.197},
}};

// Thesis §3.4: raymarching the 60^3 volume took 32-37 ms per frame on the Quadro FX 5800.
inline constexpr double kThesisRaymarchMs[2] = {32.0, 37.0};

}  // namespace masav::app

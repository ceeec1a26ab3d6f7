#pragma once
// A small SPH run on the CPU reference and the resume state it exports: the valid checkpoint the
// field and fuzz tests of checkpoints corrupt (tests/test_sph_checkpoint_fields.cpp,
// tests/test_checkpoint_fuzz.cpp). The simulation stays, for restoring states into.
#include <memory>
#include <string>

#include "engine/core/error.h"
#include "engine/cpu/cpu_backend.h"
#include "engine/sph/sph_checkpoint.h"
#include "engine/sph/sph_presets.h"
#include "engine/sph/sph_simulation.h"

namespace masav::test {

struct CheckpointCase {
  SphScene scene;
  std::unique_ptr<cpu::CpuBackend> cpu = std::make_unique<cpu::CpuBackend>(1);
  std::unique_ptr<SphSimulation> sim;
  SphResumeState state;

  CheckpointCase(const SphScene& s, uint64_t steps) : scene(s) {
    sim = std::make_unique<SphSimulation>(*cpu, scene);
    sim->run(steps);
    state = sim->export_resume_state();
  }
};

// The message of reading `path`, "" when it loads.
inline std::string checkpoint_read_error(const std::string& path) {
  try {
    read_sph_checkpoint(path);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

}  // namespace masav::test

#pragma once
// The demo's "simulated time per second" for stepped scenes (SPH): how many steps a frame runs so
// that the simulation advances at the rate asked for, as far as the device allows, and the rate
// it achieves. Defaults follow the device class: a CPU device (the CPU reference, lavapipe)
// steps a smaller fluid at a lower rate, so that the first seconds show the fluid falling there
// too.
#include <cstdint>
#include <string>

namespace masav::app {

struct SimRateDefaults {
  double seconds_per_second;  // simulated seconds per wall-clock second
  uint32_t max_particles;     // the demo starts an SPH scene with at most this many
  const char* device_class;   // "CPU device" or "GPU"
};
// device_type: Capabilities::device_type ("cpu", "discrete", "integrated", ...).
SimRateDefaults sim_rate_defaults(const std::string& device_type);

// The particle count the demo starts an SPH scene with: `count` when the scene file or --set gave
// it (`given`), or when it fits `max_particles` (0: no limit); else max_particles.
uint32_t demo_particle_count(uint32_t count, bool given, uint32_t max_particles);

// Steps for the next frame: enough for `target_s_per_s` over a frame of `frame_s` wall seconds at
// steps of `dt_s`, but no more than fit in `budget_ms` at `step_ms` each (the device's pace), and
// between 1 and `max_steps`.
uint32_t steps_for_rate(double target_s_per_s, double frame_s, double dt_s, double step_ms,
                        double budget_ms, uint32_t max_steps);

// The achieved rate, smoothed over about a second of frames.
class RateMeter {
 public:
  void reset() { rate_ = 0, have_ = false; }
  // A frame that advanced the simulation by sim_s in wall_s.
  void add(double sim_s, double wall_s);
  double rate() const { return rate_; }

 private:
  double rate_ = 0;
  bool have_ = false;
};

}  // namespace masav::app

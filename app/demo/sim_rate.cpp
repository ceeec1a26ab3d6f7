#include "app/demo/sim_rate.h"

#include <algorithm>
#include <cmath>

namespace masav::app {

SimRateDefaults sim_rate_defaults(const std::string& device_type) {
  // Measured on a loaded 2-core VM (`masav sph --preset water`, 200 steps): lavapipe steps 1,024
  // particles at 373 steps/s with dt 0.52 ms (0.19 simulated s per s if it did nothing else),
  // 2,048 at 104 steps/s (0.04 s/s), 4,096 at 65 steps/s (0.02 s/s: the cube barely moves in
  // the first seconds); the CPU reference is about 1.5x faster. With frames shared between
  // steps and drawing, 1,024 particles at 0.1 s/s show the cube falling within 3 s. A GPU runs
  // the scene's own count in real time.
  if (device_type == "cpu") return {0.1, 1024, "CPU device"};
  return {1.0, 0, "GPU"};
}

uint32_t demo_particle_count(uint32_t count, bool given, uint32_t max_particles) {
  if (given || max_particles == 0 || count <= max_particles) return count;
  return max_particles;
}

uint32_t steps_for_rate(double target_s_per_s, double frame_s, double dt_s, double step_ms,
                        double budget_ms, uint32_t max_steps) {
  max_steps = std::max(1u, max_steps);
  if (!(target_s_per_s > 0) || !(frame_s > 0) || !(dt_s > 0)) return 1;
  double steps = std::ceil(target_s_per_s * frame_s / dt_s);
  if (step_ms > 0 && budget_ms > 0) steps = std::min(steps, std::floor(budget_ms / step_ms));
  return uint32_t(std::clamp(steps, 1.0, double(max_steps)));
}

void RateMeter::add(double sim_s, double wall_s) {
  if (!(wall_s > 0)) return;
  const double r = sim_s / wall_s;
  // Weight by the frame's length: about one second of frames dominates the average.
  const double w = std::min(1.0, wall_s);
  rate_ = have_ ? (1 - w) * rate_ + w * r : r;
  have_ = true;
}

}  // namespace masav::app

#pragma once
// The backend a kernel-test binary runs against (chosen with --backend=NAME) and the CPU
// reference it is compared with. Test bodies never know which backend they run on.
#include <memory>
#include <string>

#include "engine/kernels/backend.h"

namespace masav::test {

Backend& backend();    // the backend under test
Backend& reference();  // the CPU reference (a separate instance)
const std::string& backend_name();
// The tuning options the run was given (--tune=KEY=VALUE), and a new backend of the same kind
// with other options (a test that compares two settings of one option).
const Tuning& tuning();
std::unique_ptr<Backend> backend_with(const Tuning& t);
bool is_lavapipe();  // Vulkan on Mesa's CPU driver
// Whether the SPH neighbour sums' order follows a particle's lane: Vulkan's cooperative walk
// (lavapipe's default, compute/sph_walk_choice.h) rotates a row's candidates by the lane, so
// the same particle at another index (another range, another rank) sums in another order. Every
// other walk sums each particle's neighbours in one order.
bool sph_sums_follow_lanes();
// The backend under test created once more with loop counting on (Backend::take_max_loop_ticks):
// the "loop limit" suite's. Only Vulkan counts; on the others that suite is skipped.
Backend& loop_counter();

}  // namespace masav::test

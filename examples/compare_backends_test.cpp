// The pattern to copy into your own test suite: every kernel a test cares about cross-checked
// between two backends, with masav's own tolerances, as doctest cases. A backend this machine
// does not have is skipped with a message, never counted as passed.
#define DOCTEST_CONFIG_IMPLEMENT_WITH_MAIN
#include <doctest/doctest.h>
#include <masav/masav.h>

#include <algorithm>

namespace {

bool usable(const std::string& name) {
  const auto names = masav::usable_backends();
  return std::find(names.begin(), names.end(), name) != names.end();
}

}  // namespace

TEST_CASE("vulkan computes what the CPU reference computes") {
  if (!usable("vulkan")) {
    MESSAGE("skipped: no Vulkan device on this machine");
    return;
  }
  auto cpu = masav::open_backend("cpu");
  auto vulkan = masav::open_backend("vulkan");
  for (const char* kernel : {"radix_sort", "grid_assign_cells", "sph_density", "raymarch"}) {
    CAPTURE(kernel);
    masav::CrossCheckOptions options;
    options.points = 4096;  // small enough for a unit test
    const auto report = masav::cross_check(kernel, *vulkan, *cpu, options);
    INFO(masav::report_text(report));
    CHECK(report.pass());
  }
}

TEST_CASE("a kernel that is not in the list is refused by name") {
  auto cpu = masav::open_backend("cpu");
  CHECK_THROWS_WITH_AS(masav::cross_check("no_such_kernel", *cpu, *cpu),
                       doctest::Contains("no_such_kernel"), masav::Error);
}

// Entry point of the per-backend kernel tests. `--backend=NAME` picks the backend and each
// `--tune=KEY=VALUE` sets one of its tuning options (engine/core/tuning.h). A backend
// that is not built or has no device exits 77 (ctest: skipped, never passed) after printing why;
// MASAV_REQUIRE_BACKENDS=a,b turns such a skip into a failure (CI requires vulkan and cpu).
// Under Vulkan, every validation-layer message fails the test that caused it. The variables masav
// honours (MASAV_VK_VALIDATION, MASAV_CACHE_DIR, ...: app/host_environment.h) are read here, as
// the CLI reads them, and passed to the backends: the libraries never read the environment.
#define DOCTEST_CONFIG_IMPLEMENT
#include <doctest/doctest.h>
#include <fmt/format.h>

#include <cstdlib>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "app/host_environment.h"
#include "engine/core/error.h"
#include "engine/cpu/cpu_backend.h"
#include "registry/backends.h"
#include "tests/backend_fixture.h"
#if MASAV_HAVE_VULKAN
#include "compute/device/vk_context.h"
#include "compute/sph_walk_choice.h"
#endif

namespace masav::test {
namespace {
std::unique_ptr<Backend> g_backend;
std::unique_ptr<Backend> g_reference;
std::unique_ptr<Backend> g_loop_counter;
std::string g_name;
std::vector<std::string> g_stray_validation;  // messages outside any test case
// The environment's settings, read once in main (a null until then).
std::unique_ptr<app::HostRequest> g_host;

// The host's request with other tuning and loop counting.
BackendRequest host_request(const Tuning& t, bool count_loop_ticks = false) {
  BackendRequest r = g_host->get();
  r.tuning = t;
  r.count_loop_ticks = count_loop_ticks;
  return r;
}
}  // namespace

Backend& backend() {
  return *g_backend;
}
Backend& reference() {
  return *g_reference;
}
Backend& loop_counter() {
  return *g_loop_counter;
}
const std::string& backend_name() {
  return g_name;
}
bool is_lavapipe() {
  return g_name == "vulkan" && g_backend->caps().device_type == "cpu";
}
const Tuning& tuning() {
  return g_backend->tuning();
}
std::unique_ptr<Backend> backend_with(const Tuning& t) {
  return create_backend(g_name, "", host_request(t));
}
bool sph_sums_follow_lanes() {
#if MASAV_HAVE_VULKAN
  return g_name == "vulkan" &&
         vk::sph_coop_walk(g_backend->tuning().vulkan, g_backend->caps().device_type);
#else
  return false;
#endif
}

}  // namespace masav::test

namespace {

bool required(const std::string& name) {
  const char* req = std::getenv("MASAV_REQUIRE_BACKENDS");
  if (!req) return false;
  std::stringstream ss(req);
  std::string item;
  while (std::getline(ss, item, ','))
    if (item == name) return true;
  return false;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace masav;
  std::string name = "cpu";
  Tuning tuning;
  std::vector<char*> rest;
  for (int i = 0; i < argc; ++i) {
    std::string a = argv[i];
    if (a.rfind("--backend=", 0) == 0) {
      name = a.substr(10);
    } else if (a.rfind("--tune=", 0) == 0) {
      try {
        set_tuning(tuning, a.substr(7));
      } catch (const Error& e) {
        fmt::print(stderr, "{}\n", e.what());
        return 2;
      }
    } else {
      rest.push_back(argv[i]);
    }
  }
  test::g_name = name;

#if MASAV_HAVE_VULKAN
  masav::vk::set_validation_handler([](const std::string& msg) {
    if (doctest::is_running_in_test)
      FAIL_CHECK(msg);
    else
      test::g_stray_validation.push_back(msg);
  });
#endif

  try {
    test::g_host = std::make_unique<app::HostRequest>(app::read_host_environment());
  } catch (const Error& e) {
    fmt::print(stderr, "{}\n", e.what());
    return 2;
  }
  BackendStatus status;
  for (const auto& s : list_backends(test::g_host->get()))
    if (s.name == name) status = s;
  if (status.name.empty()) {
    fmt::print(stderr, "unknown backend '{}' (vulkan, cuda, cpu)\n", name);
    return 2;
  }
  if (!status.available) {
    fmt::print("SKIPPED: backend '{}' is not available here: {}\n", name, status.reason);
    if (required(name)) {
      fmt::print(stderr, "FAILED: MASAV_REQUIRE_BACKENDS requires '{}'\n", name);
      return 1;
    }
    return 77;
  }
  try {
    test::g_backend = create_backend(name, "", test::host_request(tuning));
  } catch (const Error& e) {
    // The backend reports a device, so failing to create it is a bug, not a skip.
    fmt::print(stderr, "FAILED: backend '{}' lists a usable device but could not be created: {}\n",
               name, e.what());
    return 1;
  }
  test::g_reference = std::make_unique<cpu::CpuBackend>();
  const auto& c = test::g_backend->caps();
  fmt::print("backend {}: {} ({}, {}), subgroup {}, max buffer {} MiB{}\n", name, c.device_name,
             c.device_type, c.driver, c.subgroup_size, c.max_buffer_bytes >> 20,
             describe(tuning).empty() ? "" : ", tuned " + describe(tuning));

  // The loop-limit suite needs a backend that counts loop iterations.
  try {
    auto counter = create_backend(name, "", test::host_request(tuning, true));
    if (counter->take_max_loop_ticks()) test::g_loop_counter = std::move(counter);
  } catch (const Error& e) {
    fmt::print(stderr, "FAILED: backend '{}' could not be created to count loops: {}\n", name,
               e.what());
    return 1;
  }

  doctest::Context ctx;
  ctx.applyCommandLine(int(rest.size()), rest.data());
  if (!test::g_loop_counter) {
    fmt::print(
        "SKIPPED: the \"loop limit\" suite: the {} backend does not count loop "
        "iterations (its device has no loop limit to test)\n",
        name);
    ctx.addFilter("test-suite-exclude", "loop limit");
  }
  if (name != "vulkan") {
    fmt::print(
        "SKIPPED: the \"vulkan backend\" suite: it builds Vulkan backends of its own "
        "options (this run is {})\n",
        name);
    ctx.addFilter("test-suite-exclude", "vulkan backend");
  }
  int rc = ctx.run();
  test::g_loop_counter.reset();
  test::g_backend.reset();
  test::g_reference.reset();
  if (!test::g_stray_validation.empty()) {
    for (const auto& m : test::g_stray_validation) fmt::print(stderr, "{}\n", m);
    fmt::print(stderr, "FAILED: {} validation message(s) outside test cases\n",
               test::g_stray_validation.size());
    rc = rc ? rc : 1;
  }
  return rc;
}

// Cross-check rows that are not comparisons (issue 45, class 11): a kernel that one backend
// refuses (a buffer over its limit) is "not compared", with the backend, its message and the size
// that fits; it is counted apart from failures, and a kernel that truly disagrees still does.
#include <doctest/doctest.h>

#include <string>
#include <vector>

#include "engine/core/limit_error.h"
#include "engine/cpu/cpu_backend.h"
#include "engine/verify/cross_check.h"
#include "registry/check_catalog.h"
#include "registry/scene_catalog.h"

using namespace masav;
using scene::CheckInputs;

namespace {

bool has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// The size refusal check_fits gives on a device with 1 MiB buffers.
[[noreturn]] void refuse_1mib(const Backend& b) {
  throw LimitError(b.name(), "create_buffer",
                   "buffer 'grid cell start' needs 2097152 elements of 4 bytes (8 MiB), over "
                   "this device's 1 MiB per buffer (test)",
                   "use at most 262144 elements here, or a device with larger buffers", 1 << 20);
}

verify::KernelCheck words_check(const std::string& kernel, std::function<void(Backend&)> before) {
  return verify::exact_check(kernel, [before](Backend& be, const CheckInputs&) {
    before(be);
    return verify::CheckOutputs{{"words", std::vector<uint32_t>(16, 7), {}}};
  });
}

}  // namespace

TEST_CASE("cross-check: a kernel one backend refuses is not compared, not a failure") {
  cpu::CpuBackend a(1), b(1);
  const CheckInputs in;
  const std::vector<verify::KernelCheck> checks = {
      words_check("refused",
                  [&](Backend& be) {
                    if (&be == &a) refuse_1mib(be);
                  }),
      words_check("fine", [](Backend&) {}), words_check("refused_by_reference", [&](Backend& be) {
        if (&be == &b) refuse_1mib(be);
      })};
  const verify::CrossCheckReport r =
      verify::cross_check(a, b, {"refused", "fine", "refused_by_reference"}, in, checks);
  CHECK_FALSE(r.pass());
  CHECK(r.failures() == 0);
  CHECK(r.not_compared() == 2);
  CHECK(r.rows[0].not_compared);
  CHECK_FALSE(r.rows[0].pass);
  CHECK(r.rows[0].refused_by == "cpu (checked)");
  CHECK(r.rows[0].limit_bytes == 1 << 20);
  CHECK(r.rows[0].advice == "use at most 262144 elements here, or a device with larger buffers");
  CHECK(r.rows[1].pass);
  CHECK(r.rows[2].refused_by == "cpu (reference)");

  const std::string text = verify::format_report(r);
  CHECK(has(text,
            "refused                exact       not compared: cpu (checked) refused it: "
            "create_buffer: buffer 'grid cell start' needs"));
  CHECK(has(text, "cross-check incomplete: 1 of 3 kernels agree, 2 not compared"));
  CHECK_FALSE(has(text, "FAIL"));
  const std::string json = verify::report_json(r);
  CHECK(has(json, "\"not_compared\": 2"));
  CHECK(has(json, "\"failures\": 0"));
  CHECK(has(json, "\"outcome\": \"not compared\""));
  CHECK(has(json, "\"refused_by\": \"cpu (checked)\""));
  CHECK(has(json, "\"limit_bytes\": 1048576"));
  const std::string summary = verify::failure_summary(r);
  CHECK(has(summary, "refused not compared: cpu (checked) refused it (create_buffer: buffer"));
  CHECK_FALSE(has(summary, "disagrees"));
}

TEST_CASE("cross-check: a disagreeing kernel still disagrees beside a refused one") {
  cpu::CpuBackend a(1), b(1);
  const CheckInputs in;
  const std::vector<verify::KernelCheck> checks = {
      words_check("refused",
                  [&](Backend& be) {
                    if (&be == &a) refuse_1mib(be);
                  }),
      verify::exact_check("wrong", [&](Backend& be, const CheckInputs&) {
        return verify::CheckOutputs{{"words", std::vector<uint32_t>(16, &be == &a ? 8 : 7), {}}};
      })};
  const verify::CrossCheckReport r = verify::cross_check(a, b, {"refused", "wrong"}, in, checks);
  CHECK(r.failures() == 1);
  CHECK(r.not_compared() == 1);
  CHECK(has(verify::format_report(r), "cross-check FAILED: 0 of 2 kernels agree, 1 not compared"));
  CHECK(has(verify::failure_summary(r),
            "cpu disagrees with cpu on wrong; refused not compared: cpu (checked)"));
  CHECK(has(verify::report_json(r), "\"outcome\": \"disagrees\""));
}

TEST_CASE("cross-check: the particle scene suggests the largest grid a refusing device holds") {
  cpu::CpuBackend a(1), b(1);
  scene::ParamSet p = scene::default_params(scene::find_scene_type("particles"));
  p.set("particles.count", int64_t(2000));
  p.set("particles.grid_cells", int64_t(128));
  std::vector<verify::KernelCheck> checks = verify::kernel_checks();
  for (auto& c : checks)
    if (c.kernel == "grid_cell_ranges") {
      auto run = c.run;
      c.run = [&a, run](Backend& be, const CheckInputs& in) {
        if (&be == &a) refuse_1mib(be);
        return run(be, in);
      };
    }
  const verify::CrossCheckReport r =
      verify::cross_check_scene(a, b, scene::find_scene_type("particles"), p, checks);
  CHECK(r.failures() == 0);
  CHECK(r.not_compared() == 1);
  for (const auto& row : r.rows)
    if (row.kernel == "grid_cell_ranges")
      CHECK(has(row.advice,
                "set particles.grid_cells <= 64 (its 64^3-cell tables then fit the 1 "
                "MiB per buffer)"));
  // lavapipe's 128 MiB per binding and the largest legal grid: 322^3 cells of 4 bytes fit.
  CHECK(has(scene::find_scene_type("particles")
                .fit_advice(
                    [&] {
                      scene::ParamSet q = p;
                      q.set("particles.grid_cells", int64_t(512));
                      return q;
                    }(),
                    uint64_t(128) << 20),
            "set particles.grid_cells <= 322 "));
  // A refusal the grid does not cause leaves the refusal's own remedy.
  CHECK(scene::find_scene_type("particles").fit_advice(p, uint64_t(64) << 20).empty());
}

// `masav verify scene.toml`: the cross-check alone -- every kernel the scene uses, on the chosen
// backend and a second one, with identical inputs; the report printed and saved as JSON. Needs
// no renderer, so it runs wherever the backends do.
#include <fmt/format.h>

#include "app/commands.h"
#include "app/host_environment.h"
#include "app/scene_options.h"
#include "engine/core/error.h"
#include "engine/util/json_writer.h"
#include "engine/verify/cross_check.h"
#include "registry/backends.h"
#include "registry/check_catalog.h"

namespace masav::app {
namespace {

struct VerifyOptions {
  SceneChoice scene;
  BackendChoice choice;
  std::string reference;  // "" = the scene's verify.reference
  std::string json = "out/verify.json";
};

int run_verify(const VerifyOptions& o) {
  refuse_set_conflict(o.scene, !o.reference.empty(), "--reference", "verify.reference");
  scene::SceneFile f = load_scene(o.scene);
  if (!o.reference.empty()) f.params.set("verify.reference", o.reference);
  const std::optional<KernelId> fault = fault_kernel(o.choice);
  auto backend = open_backend(o.choice);
  const HostRequest request(host_environment());
  auto reference =
      verify::open_reference(*backend, f.params.get_text("verify.reference"), request.get());
  const verify::CrossCheckReport r =
      verify::cross_check_scene(*backend, *reference, f.params, fault);
  fmt::print("{}", verify::format_report(r));
  if (!o.json.empty()) {
    write_file_atomic(o.json, verify::report_json(r));
    fmt::print("wrote {}\n", o.json);
  }
  if (r.pass()) return 0;
  // Nothing compared is not agreement: a distinct status, so scripts can tell "too big for this
  // device" (with the size that fits in the summary) from "computes something else".
  const bool incomplete = r.failures() == 0;
  fmt::print(stderr, "masav: cross-check {}: {}\n", incomplete ? "incomplete" : "failed",
             verify::failure_summary(r));
  return incomplete ? kExitNotCompared : 1;
}

}  // namespace

void add_verify_command(CLI::App& app) {
  static VerifyOptions o;
  auto* cmd = add_scene_command(app, "verify",
                                "cross-check every kernel a scene uses against a "
                                "second backend (report printed and saved as JSON)",
                                o, run_verify);
  cmd->add_option("--reference,-r", o.reference,
                  "second backend (default: the scene's verify.reference, auto)")
      ->check(CLI::IsMember({"auto", "cpu", "vulkan", "cuda"}));
  add_fault_option(*cmd, o.choice);
  cmd->add_option("--json", o.json, "write the report here (\"\" for none)")->capture_default_str();
}

}  // namespace masav::app

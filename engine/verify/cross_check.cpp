#include "engine/verify/cross_check.h"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <optional>

#include "engine/core/error.h"
#include "engine/util/json_writer.h"

namespace masav::verify {
namespace {

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

// Arms the backend's fault for the one check of that kernel, so no other row sees it.
class ArmedFault {
 public:
  ArmedFault(Backend& b, std::optional<KernelId> fault, const std::string& kernel) : b_(b) {
    if (fault && kernel_name(*fault) == kernel) b_.inject_fault(fault);
  }
  ~ArmedFault() { b_.inject_fault(std::nullopt); }
  ArmedFault(const ArmedFault&) = delete;
  ArmedFault& operator=(const ArmedFault&) = delete;

 private:
  Backend& b_;
};

}  // namespace

bool CrossCheckReport::pass() const {
  return failures() == 0;
}
size_t CrossCheckReport::failures() const {
  size_t f = 0;
  for (const auto& r : rows) f += !r.pass;
  return f;
}

CrossCheckReport cross_check(Backend& backend, Backend& reference,
                             const std::vector<std::string>& kernels, const CheckInputs& in,
                             const std::vector<KernelCheck>& checks,
                             std::optional<KernelId> fault) {
  CrossCheckReport rep;
  rep.backend = backend.name();
  rep.device = backend.caps().device_name;
  rep.reference = reference.name();
  rep.reference_device = reference.caps().device_name;
  rep.points = in.points;
  rep.seed = in.seed;
  for (const auto& kernel : kernels) {
    CheckRow row;
    row.kernel = kernel;
    const KernelCheck* check = nullptr;
    for (const auto& c : checks)
      if (c.kernel == kernel) check = &c;
    if (!check) {
      row.error = "no cross-check is registered for this kernel";
      rep.rows.push_back(row);
      continue;
    }
    row.kind = check->kind;
    try {
      auto t0 = std::chrono::steady_clock::now();
      CheckOutputs got = [&] {
        const ArmedFault armed(backend, fault, kernel);
        return check->run(backend, in);
      }();
      row.ms_backend = ms_since(t0);
      t0 = std::chrono::steady_clock::now();
      const CheckOutputs want = check->run(reference, in);
      row.ms_reference = ms_since(t0);
      const Verdict v = check->compare(got, want, in);
      row.pass = v.pass;
      row.metrics = v.metrics;
      row.tolerance = v.tolerance;
      row.numbers = v.numbers;
    } catch (const Error& e) {
      row.error = e.what();
    }
    rep.rows.push_back(row);
  }
  return rep;
}

CrossCheckReport cross_check_scene(Backend& backend, Backend& reference,
                                   const scene::SceneType& type, const scene::ParamSet& params,
                                   const std::vector<KernelCheck>& checks,
                                   std::optional<KernelId> fault) {
  std::vector<std::string> kernels;
  for (KernelId k : type.kernels(params)) kernels.emplace_back(kernel_name(k));
  CrossCheckReport r =
      cross_check(backend, reference, kernels, type.check_inputs(params), checks, fault);
  r.scene = type.name;
  return r;
}

std::unique_ptr<Backend> open_reference(const Backend& chosen, const std::string& choice,
                                        const BackendFactory& factory) {
  const BackendRequest same{.tuning = chosen.tuning()};
  if (choice != "auto") return factory.create(choice, "", same);
  // The other GPU backend when the chosen one is a GPU backend; a GPU backend when the chosen
  // one is the CPU reference; else (none available, or it fails to open) the CPU reference.
  const std::string me = chosen.name();
  const std::vector<std::string> others =
      me == "vulkan" ? std::vector<std::string>{"cuda"}
                     : (me == "cuda" ? std::vector<std::string>{"vulkan"}
                                     : std::vector<std::string>{"vulkan", "cuda"});
  for (const std::string& other : others)
    for (const auto& s : factory.list())
      if (s.name == other && s.available) {
        try {
          return factory.create(other, "", same);
        } catch (const Error&) {
        }
      }
  return factory.create("cpu", "", same);
}

std::string format_report(const CrossCheckReport& r) {
  std::string out =
      fmt::format("cross-check of the '{}' scene: {} ({}) against {} ({}), {} points, seed {}\n",
                  r.scene, r.backend, r.device, r.reference, r.reference_device, r.points, r.seed);
  for (const auto& row : r.rows) {
    out += fmt::format("  {:<22} {:<11} {}  ", row.kernel, check_kind_name(row.kind),
                       row.pass ? "PASS" : "FAIL");
    if (!row.error.empty())
      out += "error: " + row.error + "\n";
    else
      out += fmt::format("{}; allowed: {}\n", row.metrics, row.tolerance);
  }
  out += fmt::format("cross-check {}: {} of {} kernels agree\n", r.pass() ? "passed" : "FAILED",
                     r.rows.size() - r.failures(), r.rows.size());
  return out;
}

std::string report_json(const CrossCheckReport& r) {
  JsonWriter j;
  j.begin_object();
  j.field("scene", r.scene).field("pass", r.pass());
  j.key("backend").begin_object().field("name", r.backend).field("device", r.device).end_object();
  j.key("reference").begin_object().field("name", r.reference).field("device", r.reference_device);
  j.end_object();
  j.field("points", r.points).field("seed", r.seed);
  j.key("kernels").begin_array();
  for (const auto& row : r.rows) {
    j.begin_object().field("kernel", row.kernel).field("kind", check_kind_name(row.kind));
    j.field("pass", row.pass).field("metrics", row.metrics).field("tolerance", row.tolerance);
    if (!row.error.empty()) j.field("error", row.error);
    j.key("numbers").begin_object();
    for (const auto& [k, v] : row.numbers) j.field(k, v);
    j.end_object();
    j.field("ms_backend", row.ms_backend).field("ms_reference", row.ms_reference);
    j.end_object();
  }
  j.end_array().end_object();
  return j.str() + "\n";
}

std::string failure_summary(const CrossCheckReport& r) {
  std::string kernels;
  for (const auto& row : r.rows)
    if (!row.pass) kernels += (kernels.empty() ? "" : ", ") + row.kernel;
  return fmt::format("{} disagrees with {} on {}", r.backend, r.reference, kernels);
}

}  // namespace masav::verify

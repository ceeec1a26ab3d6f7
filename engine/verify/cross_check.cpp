#include "engine/verify/cross_check.h"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <optional>

#include "engine/core/error.h"
#include "engine/core/limit_error.h"
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

// What a row is, in the report's words.
const char* outcome(const CheckRow& row) {
  return row.pass ? "agrees" : (row.not_compared ? "not compared" : "disagrees");
}

// A backend that throws cannot run the kernel: nothing was compared. The message without its
// remedy; the remedy (or the scene's better advice) is the row's advice.
void refuse(CheckRow& row, const Backend& who, const char* role, const Error& e) {
  row.not_compared = true;
  row.refused_by = fmt::format("{} ({})", who.name(), role);
  row.error = e.kernel().empty() ? e.problem() : fmt::format("{}: {}", e.kernel(), e.problem());
  row.advice = e.remedy();
  if (const auto* limit = dynamic_cast<const LimitError*>(&e))
    row.limit_bytes = limit->limit_bytes();
}

}  // namespace

bool CrossCheckReport::pass() const {
  return failures() == 0 && not_compared() == 0;
}
size_t CrossCheckReport::failures() const {
  size_t f = 0;
  for (const auto& r : rows) f += !r.pass && !r.not_compared;
  return f;
}
size_t CrossCheckReport::not_compared() const {
  size_t n = 0;
  for (const auto& r : rows) n += r.not_compared;
  return n;
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
    std::optional<CheckOutputs> got, want;
    auto t0 = std::chrono::steady_clock::now();
    try {
      const ArmedFault armed(backend, fault, kernel);
      got = check->run(backend, in);
    } catch (const Error& e) {
      refuse(row, backend, "checked", e);
    }
    row.ms_backend = ms_since(t0);
    if (got) {
      t0 = std::chrono::steady_clock::now();
      try {
        want = check->run(reference, in);
      } catch (const Error& e) {
        refuse(row, reference, "reference", e);
      }
      row.ms_reference = ms_since(t0);
    }
    if (got && want) {
      try {
        const Verdict v = check->compare(*got, *want, in);
        row.pass = v.pass;
        row.metrics = v.metrics;
        row.tolerance = v.tolerance;
        row.numbers = v.numbers;
      } catch (const Error& e) {
        row.error = e.what();
      }
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
  if (type.fit_advice)
    for (CheckRow& row : r.rows)
      if (row.limit_bytes)
        if (std::string a = type.fit_advice(params, row.limit_bytes); !a.empty())
          row.advice = std::move(a);
  return r;
}

std::unique_ptr<Backend> open_reference(const Backend& chosen, const std::string& choice,
                                        const BackendFactory& factory,
                                        const BackendRequest& request) {
  BackendRequest same = request;
  same.tuning = chosen.tuning();
  // The CPU backend as a reference is the fp64 oracle, whatever precision the chosen one's
  // options picked for itself.
  same.tuning.cpu.sph_precision = CpuSphPrecision::fp64;
  if (choice != "auto") return factory.create(choice, "", same);
  // The other GPU backend when the chosen one is a GPU backend; a GPU backend when the chosen
  // one is the CPU reference; else (none available, or it fails to open) the CPU reference.
  const std::string me = chosen.name();
  const std::vector<std::string> others =
      me == "vulkan" ? std::vector<std::string>{"cuda"}
                     : (me == "cuda" ? std::vector<std::string>{"vulkan"}
                                     : std::vector<std::string>{"vulkan", "cuda"});
  for (const std::string& other : others)
    for (const auto& s : factory.list(same))
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
    out += fmt::format("  {:<22} {:<11} ", row.kernel, check_kind_name(row.kind));
    if (row.not_compared)
      out += fmt::format("not compared: {} refused it: {}; {}\n", row.refused_by, row.error,
                         row.advice);
    else if (!row.error.empty())
      out += fmt::format("{}  error: {}\n", row.pass ? "PASS" : "FAIL", row.error);
    else
      out += fmt::format("{}  {}; allowed: {}\n", row.pass ? "PASS" : "FAIL", row.metrics,
                         row.tolerance);
  }
  const size_t agree = r.rows.size() - r.failures() - r.not_compared();
  const std::string skipped =
      r.not_compared() ? fmt::format(", {} not compared", r.not_compared()) : "";
  if (r.pass())
    out += fmt::format("cross-check passed: {} of {} kernels agree\n", agree, r.rows.size());
  else if (r.failures())
    out += fmt::format("cross-check FAILED: {} of {} kernels agree{}\n", agree, r.rows.size(),
                       skipped);
  else
    out += fmt::format(
        "cross-check incomplete: {} of {} kernels agree{} (a backend refused them: "
        "nothing was compared there)\n",
        agree, r.rows.size(), skipped);
  return out;
}

std::string report_json(const CrossCheckReport& r) {
  JsonWriter j;
  j.begin_object();
  j.field("scene", r.scene).field("pass", r.pass());
  j.field("failures", uint64_t(r.failures())).field("not_compared", uint64_t(r.not_compared()));
  j.key("backend").begin_object().field("name", r.backend).field("device", r.device).end_object();
  j.key("reference").begin_object().field("name", r.reference).field("device", r.reference_device);
  j.end_object();
  j.field("points", r.points).field("seed", r.seed);
  j.key("kernels").begin_array();
  for (const auto& row : r.rows) {
    j.begin_object().field("kernel", row.kernel).field("kind", check_kind_name(row.kind));
    j.field("pass", row.pass).field("outcome", outcome(row));
    j.field("metrics", row.metrics).field("tolerance", row.tolerance);
    if (!row.error.empty()) j.field("error", row.error);
    if (row.not_compared) {
      j.field("refused_by", row.refused_by).field("advice", row.advice);
      if (row.limit_bytes) j.field("limit_bytes", row.limit_bytes);
    }
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
  std::string kernels, out;
  for (const auto& row : r.rows)
    if (!row.pass && !row.not_compared) kernels += (kernels.empty() ? "" : ", ") + row.kernel;
  if (!kernels.empty())
    out = fmt::format("{} disagrees with {} on {}", r.backend, r.reference, kernels);
  for (const auto& row : r.rows)
    if (row.not_compared)
      out += fmt::format("{}{} not compared: {} refused it ({}); {}", out.empty() ? "" : "; ",
                         row.kernel, row.refused_by, row.error, row.advice);
  return out;
}

}  // namespace masav::verify

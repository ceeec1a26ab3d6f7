#include "app/bench_common.h"

#include <fmt/format.h>

#include <algorithm>
#include <cstdio>
#include <ctime>
#include <thread>

#include "app/build_info.h"
#include "app/host_environment.h"
#include "engine/core/error.h"
#include "registry/backends.h"

namespace masav::app {

TimingStats summarize(std::vector<double> s) {
  TimingStats t;
  t.reps = int(s.size());
  if (s.empty()) return t;
  std::sort(s.begin(), s.end());
  t.min_ms = s.front();
  t.max_ms = s.back();
  t.median_ms = s.size() % 2 ? s[s.size() / 2] : 0.5 * (s[s.size() / 2 - 1] + s[s.size() / 2]);
  return t;
}

std::vector<double> time_on_device(Backend& b, int warmup, int reps,
                                   const std::function<void()>& setup,
                                   const std::function<void()>& work) {
  std::vector<double> out;
  for (int i = 0; i < warmup + reps; ++i) {
    setup();
    b.finish();
    b.reset_timestamps();
    const TimestampId t0 = b.timestamp();
    work();
    const TimestampId t1 = b.timestamp();
    b.finish();
    if (i >= warmup) out.push_back((b.timestamp_ns(t1) - b.timestamp_ns(t0)) * 1e-6);
  }
  return out;
}

TimingStats time_work(Backend& b, int reps, const std::function<void()>& work) {
  const auto no_setup = [] {};
  return summarize(time_on_device(b, 1, reps, no_setup, work));
}

namespace {

void note_cpu_devices(const std::vector<std::unique_ptr<Backend>>& backends,
                      const std::string& hint) {
  std::string names;
  for (const auto& b : backends)
    if (b->caps().device_type == "cpu")
      names +=
          fmt::format("{}{} ({})", names.empty() ? "" : ", ", b->name(), b->caps().device_name);
  if (names.empty() || hint.empty()) return;
  std::fflush(stdout);
  fmt::print(stderr,
             "note: {} run on the CPU; the default sizes are set for GPUs and can take minutes "
             "here ({} for a short run)\n",
             names, hint);
}

}  // namespace

std::vector<std::unique_ptr<Backend>> open_backends(const BackendChoice& choice,
                                                    const std::string& cpu_hint) {
  std::vector<std::unique_ptr<Backend>> out;
  if (choice.backend != "all") {
    out.push_back(open_backend(choice));
    note_cpu_devices(out, cpu_hint);
    return out;
  }
  for (const BackendStatus& s : list_backends(HostRequest(host_environment()).get())) {
    if (!s.available) {
      fmt::print("  ({} skipped: {})\n", s.name, s.reason);
      continue;
    }
    out.push_back(open_backend(choice, s.name, s.name == "cpu" ? "" : choice.device));
  }
  note_cpu_devices(out, cpu_hint);
  return out;
}

bool run_row(const std::string& label, const std::function<void()>& row, const char* outcome) {
  try {
    row();
    return true;
  } catch (const Error& e) {
    fmt::print("  {} {}: {}\n", label, outcome, e.what());
    return false;
  }
}

std::string backend_label(const Backend& b) {
  return fmt::format("{:<8}", b.name());
}

int for_each_backend(const std::vector<std::unique_ptr<Backend>>& backends,
                     const std::function<void(Backend&)>& body) {
  int rc = 0;
  for (const auto& b : backends)
    if (!run_row(backend_label(*b), [&] { body(*b); })) rc = 1;
  return rc;
}

void write_record_header(JsonWriter& j, const std::string& benchmark) {
  const std::time_t now = std::time(nullptr);
  char date[32];
  std::strftime(date, sizeof date, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
  j.field("benchmark", benchmark).field("date", std::string(date));
  j.key("masav").begin_object();
  j.field("version", build_info::version).field("git", build_info::git());
  j.field("compiler", build_info::compiler).field("build_type", build_info::build_type);
  j.field("cuda_architectures", build_info::cuda_architectures);
  j.end_object();
  j.key("host").begin_object().field("hardware_threads", std::thread::hardware_concurrency());
  j.end_object();
}

void write_device(JsonWriter& j, const Backend& b) {
  const Capabilities& c = b.caps();
  j.field("backend", c.backend).field("device", c.device_name).field("device_type", c.device_type);
  j.field("vendor", c.vendor).field("driver", c.driver).field("subgroup_size", c.subgroup_size);
  if (c.threads > 1) j.field("threads", c.threads);
}

void begin_row(JsonWriter& j, const Backend& b) {
  j.begin_object();
  write_device(j, b);
}

void finish_record(const JsonWriter& j, const std::string& path) {
  if (path.empty()) return;
  write_file_atomic(path, j.str() + "\n");
  fmt::print("wrote {}\n", path);
}

void add_reps_option(CLI::App& cmd, int& reps) {
  cmd.add_option("--reps", reps, "timed runs (after one warm-up)")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
}

void add_json_option(CLI::App& cmd, std::string& path) {
  cmd.add_option("--json", path, "write the results as JSON to this file");
}

}  // namespace masav::app

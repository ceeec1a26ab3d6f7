#pragma once
// Shared pieces of `masav bench`: device-timestamp timing with medians, the backends to run and
// the rows run on each, and the JSON record header (masav build, host, date).
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "app/commands.h"
#include "engine/kernels/backend.h"
#include "engine/util/json_writer.h"

namespace masav::app {

// What every benchmark added by add_bench is given: the backends (every available one unless
// --backend names one) and where its JSON record goes (none if --json is not given).
struct BenchOptions {
  BackendChoice choice{"all", ""};
  std::string json;
};

struct TimingStats {
  double median_ms = 0, min_ms = 0, max_ms = 0;
  int reps = 0;
};
TimingStats summarize(std::vector<double> samples_ms);

// Runs setup() untimed, then the work between two device timestamps; `warmup` unrecorded runs
// first. Returns the device time of each recorded run in milliseconds.
std::vector<double> time_on_device(Backend& b, int warmup, int reps,
                                   const std::function<void()>& setup,
                                   const std::function<void()>& work);

// The work's device time: `reps` runs after one warm-up, nothing to set up between them.
TimingStats time_work(Backend& b, int reps, const std::function<void()>& work);

// Backends named by --backend (all = every available one), opened; unavailable ones are
// reported on stdout and left out. With `cpu_hint` (the options that make the benchmark short),
// a backend on a CPU device (the CPU reference, lavapipe) is named up front on stderr: the
// default sizes are set for GPUs and take minutes there.
std::vector<std::unique_ptr<Backend>> open_backends(const BackendChoice& choice,
                                                    const std::string& cpu_hint = "");

// Runs one row of a benchmark table. An Error there (a feature the device lacks, a size over its
// buffers) is printed in the table as "  <label> <outcome>: <message>" and the benchmark goes
// on, so one failing device or size does not hide the others' results. False after an Error.
bool run_row(const std::string& label, const std::function<void()>& row,
             const char* outcome = "error");
// The label of a row that only names its backend: the name in the table's first column.
std::string backend_label(const Backend& b);
// `body` on each backend under run_row; the benchmark's exit code: 1 if one failed, else 0.
int for_each_backend(const std::vector<std::unique_ptr<Backend>>& backends,
                     const std::function<void(Backend&)>& body);

void write_record_header(JsonWriter& j, const std::string& benchmark);
void write_device(JsonWriter& j, const Backend& b);
// Opens a row's JSON object with the device that ran it.
void begin_row(JsonWriter& j, const Backend& b);
// Writes the JSON record (atomically) if a path was given, and says where.
void finish_record(const JsonWriter& j, const std::string& path);

// A `masav bench` subcommand: --backend, where `all` is allowed, and --device are its first
// options. When it is chosen, `run(o, j)` fills the JSON record `j` (an object opened with the
// header, the benchmark named as the subcommand) and returns the exit code; the record is then
// written where --json says, even when a backend failed.
template <class Options>
CLI::App* add_bench(CLI::App& bench, const std::string& name, const std::string& description,
                    Options& o, int (*run)(const Options&, JsonWriter&)) {
  CLI::App* cmd = bench.add_subcommand(name, description);
  add_backend_options(*cmd, o.choice, true);
  cmd->callback([name, &o, run] {
    JsonWriter j;
    j.begin_object();
    write_record_header(j, name);
    const int rc = run(o, j);
    j.end_object();
    finish_record(j, o.json);
    if (rc) throw CLI::RuntimeError(rc);
  });
  return cmd;
}

// The options every benchmark has: --reps (timed runs after one warm-up, 1..1000) and --json.
void add_reps_option(CLI::App& cmd, int& reps);
void add_json_option(CLI::App& cmd, std::string& path);

}  // namespace masav::app

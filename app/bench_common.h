#pragma once
// Shared pieces of `masav bench`: device-timestamp timing with medians, the backends to run,
// and the JSON record header (masav build, host, date).
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "app/commands.h"
#include "engine/kernels/backend.h"
#include "engine/util/json_writer.h"

namespace masav::app {

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

// Backends named by --backend (all = every available one), opened; unavailable ones are
// reported on stdout and left out.
std::vector<std::unique_ptr<Backend>> open_backends(const BackendChoice& choice);

void write_record_header(JsonWriter& j, const std::string& benchmark);
void write_device(JsonWriter& j, const Backend& b);
// Writes the JSON record (atomically) if a path was given, and says where.
void finish_record(const JsonWriter& j, const std::string& path);

// The options every benchmark has: --reps (timed runs after one warm-up, 1..1000) and --json.
void add_reps_option(CLI::App& cmd, int& reps);
void add_json_option(CLI::App& cmd, std::string& path);

}  // namespace masav::app

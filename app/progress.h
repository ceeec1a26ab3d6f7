#pragma once
// A progress bar on stderr: redrawn in place on a terminal, a line per 10% otherwise (logs), with
// the time left once a step has finished. Long commands (benchmarks, `masav volume`, `masav atom`)
// count their steps with it, so a run of minutes never looks hung.
#include <chrono>
#include <cstdint>
#include <string>

namespace masav::app {

class Progress {
 public:
  Progress(std::string what, uint64_t total);
  // `done` of `total` steps; `note` names the step now running (a row, a stage).
  void update(uint64_t done, const std::string& note = "");
  // One more step done.
  void advance(const std::string& note = "") { update(done_ + 1, note); }
  void finish();

 private:
  std::string what_;
  uint64_t total_;
  uint64_t done_ = 0;
  bool tty_;
  int last_decile_ = -1;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

// "~12 s left" from the seconds spent on `done` of `total` steps; "" before the first step ends.
std::string time_left(double elapsed_s, uint64_t done, uint64_t total);

}  // namespace masav::app

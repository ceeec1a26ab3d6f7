#pragma once
// A progress bar on stderr: redrawn in place on a terminal, a line per 10% otherwise (logs).
#include <chrono>
#include <cstdint>
#include <string>

namespace masav::app {

class Progress {
 public:
  Progress(std::string what, uint64_t total);
  void update(uint64_t done, const std::string& note = "");
  void finish();

 private:
  std::string what_;
  uint64_t total_;
  bool tty_;
  int last_decile_ = -1;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

}  // namespace masav::app

#include "app/progress.h"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>

namespace masav::app {

std::string time_left(double elapsed_s, uint64_t done, uint64_t total) {
  if (done == 0 || done >= total || !(elapsed_s > 0)) return "";
  const double left = elapsed_s / double(done) * double(total - done);
  if (left >= 120) return fmt::format("~{:.0f} min left", left / 60);
  if (left < 1) return "<1 s left";
  return fmt::format("~{:.0f} s left", left);
}

Progress::Progress(std::string what, uint64_t total)
    : what_(std::move(what)), total_(total), tty_(::isatty(2) != 0) {}

void Progress::update(uint64_t done, const std::string& note) {
  done_ = done;
  std::fflush(stdout);  // keep the order of messages when stdout is a pipe
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const double rate = s > 0 ? double(done) / s : 0;
  const double frac = total_ ? double(done) / double(total_) : 1.0;
  const std::string left = time_left(s, done, total_);
  const std::string tail =
      (left.empty() ? "" : ", " + left) + ")" + (note.empty() ? "" : "  " + note);
  if (tty_) {
    constexpr int kWidth = 30;
    const int filled = int(frac * kWidth);
    fmt::print(stderr, "\r[{}{}] {}/{} {} ({:.1f}/s{}   ", std::string(filled, '#'),
               std::string(kWidth - filled, '.'), done, total_, what_, rate, tail);
    return;
  }
  const int decile = int(frac * 10);
  if (decile == last_decile_) return;
  last_decile_ = decile;
  fmt::print(stderr, "[{:3.0f}%] {}/{} {} ({:.1f}/s{}\n", frac * 100, done, total_, what_, rate,
             tail);
}

void Progress::finish() {
  if (tty_) fmt::print(stderr, "\n");
}

}  // namespace masav::app

#pragma once
// Running another program (ffmpeg) without a shell, so that no path can be read as shell syntax,
// and with a time limit, so that a program that hangs cannot hang masav or keep its output lock.
#include <functional>
#include <string>
#include <vector>

namespace masav::app {

struct ProcessResult {
  bool started = false;    // false: it could not be run at all (see `error`)
  bool timed_out = false;  // killed after the limit
  bool stopped = false;    // killed because `stop` said so (an interrupt of masav)
  int exit_code = -1;      // its exit status when it exited
  int signal = 0;          // the signal that stopped it, when one did
  std::string error;       // why it could not start
  // "exit status 3", "stopped by signal 9", "killed after 60 s", "could not start: ..."
  std::string describe(double limit_s) const;
};

// Runs argv[0] (looked up in PATH when it has no slash) with stdin from /dev/null, in its own
// process group. After `limit_s` seconds, or once `stop` returns true (polled), the group gets
// SIGTERM, and SIGKILL 2 s later.
ProcessResult run_process(const std::vector<std::string>& argv, double limit_s,
                          const std::function<bool()>& stop = {});

}  // namespace masav::app

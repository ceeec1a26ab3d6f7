#include "app/subprocess.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <thread>

namespace masav::app {

std::string ProcessResult::describe(double limit_s) const {
  if (!started) return fmt::format("could not start: {}", error);
  if (timed_out) return fmt::format("killed after {:g} s without finishing", limit_s);
  if (stopped) return "stopped by the interrupt";
  if (signal) return fmt::format("stopped by signal {}", signal);
  return fmt::format("exit status {}", exit_code);
}

ProcessResult run_process(const std::vector<std::string>& argv, double limit_s,
                          const std::function<bool()>& stop) {
  ProcessResult r;
  if (argv.empty()) {
    r.error = "no program";
    return r;
  }
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  // A pipe closed on exec tells the parent whether exec succeeded (and errno if not).
  int status_pipe[2];
  if (pipe2(status_pipe, O_CLOEXEC) != 0) {
    r.error = std::strerror(errno);
    return r;
  }
  const pid_t pid = fork();
  if (pid < 0) {
    r.error = std::strerror(errno);
    close(status_pipe[0]);
    close(status_pipe[1]);
    return r;
  }
  if (pid == 0) {
    setpgid(0, 0);
    const int in = open("/dev/null", O_RDONLY);
    if (in >= 0) dup2(in, STDIN_FILENO);
    execvp(args[0], args.data());
    const int e = errno;
    (void)!write(status_pipe[1], &e, sizeof e);
    _exit(127);
  }
  setpgid(pid, pid);  // also here, so the group exists before any kill below
  close(status_pipe[1]);
  int exec_errno = 0;
  const bool exec_failed = read(status_pipe[0], &exec_errno, sizeof exec_errno) == sizeof exec_errno;
  close(status_pipe[0]);

  using clock = std::chrono::steady_clock;
  const auto deadline = clock::now() + std::chrono::duration<double>(limit_s);
  int status = 0;
  bool term_sent = false;
  auto kill_at = deadline;
  for (;;) {
    const pid_t w = waitpid(pid, &status, WNOHANG);
    if (w == pid) break;
    if (w < 0 && errno != EINTR) {
      r.error = std::strerror(errno);
      return r;
    }
    const auto now = clock::now();
    const bool stop_now = stop && stop();
    if (!term_sent && (now >= deadline || stop_now)) {
      kill(-pid, SIGTERM);
      term_sent = true;
      (stop_now ? r.stopped : r.timed_out) = true;
      kill_at = now + std::chrono::seconds(2);
    } else if (term_sent && now >= kill_at) {
      kill(-pid, SIGKILL);
      kill_at = now + std::chrono::hours(1);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  if (exec_failed) {
    r.error = fmt::format("{}: {}", argv[0], std::strerror(exec_errno));
    return r;
  }
  r.started = true;
  if (WIFEXITED(status)) r.exit_code = WEXITSTATUS(status);
  if (WIFSIGNALED(status)) r.signal = WTERMSIG(status);
  return r;
}

}  // namespace masav::app

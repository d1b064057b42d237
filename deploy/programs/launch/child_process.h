#pragma once
// One supervised child process: fork + exec with stdout/stderr appended to a log file. The child gets its own
// process group, so a Ctrl-C on the terminal reaches only the launcher, which forwards it (agents must not see the
// signal before the launcher knows a shutdown is under way, or it would restart them), and it dies with the launcher
// (PR_SET_PDEATHSIG), so even a SIGKILLed launcher leaves no stray process behind. POSIX / Linux only.

#include <sys/types.h>

#include <optional>
#include <string>
#include <vector>

namespace swa::launch {

class ChildProcess {
 public:
  // Starts argv[0] (a path) with the launcher's environment. Throws std::runtime_error when the log cannot be
  // opened or fork fails; a failing exec shows up as exit status 127 and a line in the log.
  ChildProcess(const std::vector<std::string>& argv, const std::string& log_path);
  ~ChildProcess();  // SIGKILLs and reaps a child still running: the owner is expected to have stopped it
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  pid_t pid() const { return pid_; }
  // Reaps without blocking. Exit status, 128 + signal if killed by one; nullopt while running.
  std::optional<int> poll();
  bool running() { return !poll().has_value(); }
  void signal(int sig);

 private:
  pid_t pid_ = -1;
  std::optional<int> status_;
};

// "exit 3", "signal 9 (Killed)".
std::string describeStatus(int status);

}  // namespace swa::launch

#pragma once
// Helpers for tests that run the SWA processes: a child process that is always reaped (SIGTERM, then SIGKILL), the
// command lines of an agent and of the agents' configuration export, a janitor that removes the Fast DDS
// shared-memory files our processes leave behind when they die by a signal, the processes left on a test's domain,
// samples a test's DDS reader received, polling with a bound, and small file and JSON helpers. POSIX only.
// (process_test.h adds what needs GoogleTest.)

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "shm_janitor.h"
#include "swa/dds/participant_id.h"
#include "swa/dds/sample_queue.h"
#include "test_domain.h"

namespace swa::testing {

namespace fs = std::filesystem;
using SteadyClock = std::chrono::steady_clock;

inline std::string readFile(const fs::path& p) {
  std::ifstream in(p);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// A number member of the JSON documents our programs write (summary.json, the simulator's summary): the first
// member `key`, depth first; true / false read as 1 / 0; NaN when absent, null, or the text is not JSON.
inline double jsonNumber(const std::string& json, const std::string& key) {
  const std::function<const nlohmann::json*(const nlohmann::json&)> find =
      [&](const nlohmann::json& j) -> const nlohmann::json* {
    if (j.is_object()) {
      if (const auto it = j.find(key); it != j.end()) return &*it;
    }
    if (j.is_structured()) {
      for (const nlohmann::json& child : j) {
        if (const nlohmann::json* hit = find(child)) return hit;
      }
    }
    return nullptr;
  };
  const nlohmann::json doc = nlohmann::json::parse(json, nullptr, /*allow_exceptions=*/false);
  const nlohmann::json* v = find(doc);
  if (v == nullptr) return std::nan("");
  if (v->is_boolean()) return v->get<bool>() ? 1.0 : 0.0;
  return v->is_number() ? v->get<double>() : std::nan("");
}

// The samples of one topic that a DDS reader of the test received: the reader's listener() queues them (on a
// middleware thread), the test moves what has arrived into `seen` with take(). Must outlive the reader.
template <class T>
struct Received {
  std::function<void(T&&)> listener() {
    return [this](T&& sample) { queue.push(std::move(sample)); };
  }
  // Moves what has arrived into `seen`, waiting up to `wait` for the first new sample.
  void take(std::chrono::milliseconds wait = std::chrono::milliseconds(0)) { queue.drain(seen, wait); }

  dds::SampleQueue<T> queue;
  std::vector<T> seen;
};

// Polls `done` every 20 ms for at most `seconds`; its last answer.
template <class Predicate>
bool waitFor(Predicate done, double seconds) {
  const auto deadline = SteadyClock::now() + std::chrono::duration<double>(seconds);
  while (!done()) {
    if (SteadyClock::now() >= deadline) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return true;
}

// PIDs of live swa_* processes whose command line names DDS domain `domain` (every child of a test gets
// --domain D), to find what a failed check left running.
inline std::vector<int> processesOnDomain(int domain) {
  std::vector<int> pids;
  const std::string needle = std::string("--domain") + '\0' + std::to_string(domain) + '\0';
  for (const auto& e : fs::directory_iterator("/proc")) {
    const std::string name = e.path().filename().string();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    const std::string cmdline = readFile(e.path() / "cmdline");
    if (cmdline.find("swa_") != std::string::npos && cmdline.find(needle) != std::string::npos &&
        readFile(e.path() / "stat").find(") Z") == std::string::npos) {
      pids.push_back(std::stoi(name));
    }
  }
  return pids;
}

// swa_agent (`binary`) for UAV `id` on DDS domain `domain`, with the configuration file `config` if one is given.
inline std::vector<std::string> agentCommand(const std::string& binary, int id, int domain,
                                             const fs::path& config = {}) {
  std::vector<std::string> argv{binary, "--id", std::to_string(id), "--domain", std::to_string(domain)};
  if (!config.empty()) argv.insert(argv.end(), {"--config", config.string()});
  return argv;
}

// The simulator's and agents' logs of a run directory (sim.log, agent<i>.log), for failure messages.
inline std::string runLogs(const fs::path& dir, std::size_t agents) {
  std::string s = "--- sim.log\n" + readFile(dir / "sim.log");
  for (std::size_t i = 0; i < agents; ++i) {
    s += "--- agent" + std::to_string(i) + ".log\n" + readFile(dir / ("agent" + std::to_string(i) + ".log"));
  }
  return s;
}

// A child process (fork + execve, stdout and stderr into `log`, this process's environment plus `extra_env`
// "KEY=value" entries, which win). The destructor never leaves it running: SIGTERM, up to 5 s for a clean exit, then
// SIGKILL, and it is always reaped.
class Child {
 public:
  Child(const std::vector<std::string>& argv, const fs::path& log, const std::vector<std::string>& extra_env = {})
      : log_(log) {
    std::vector<char*> args;
    for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    std::vector<std::string> env_strings = extra_env;
    for (char** e = environ; *e != nullptr; ++e) {
      const std::string entry = *e;
      const std::string key = entry.substr(0, entry.find('=') + 1);
      bool overridden = false;
      for (const std::string& x : extra_env) overridden = overridden || x.rfind(key, 0) == 0;
      if (!overridden) env_strings.push_back(entry);
    }
    std::vector<char*> env;
    for (std::string& e : env_strings) env.push_back(e.data());
    env.push_back(nullptr);
    const std::string log_path = log.string();
    pid_ = ::fork();
    if (pid_ == 0) {
      // Only async-signal-safe calls between fork and exec (the parent may have DDS threads).
      const int fd = ::open(log_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      if (fd >= 0) {
        ::dup2(fd, STDOUT_FILENO);
        ::dup2(fd, STDERR_FILENO);
        ::close(fd);
      }
      ::execve(args[0], args.data(), env.data());
      ::_exit(127);
    }
  }
  Child(const Child&) = delete;
  Child& operator=(const Child&) = delete;
  ~Child() { stop(); }

  pid_t pid() const { return pid_; }
  const fs::path& log() const { return log_; }
  void signal(int sig) const {
    if (pid_ > 0 && !status_) ::kill(pid_, sig);
  }

  // Exit status (128 + signal if killed by one), or nullopt if still running after `seconds`.
  std::optional<int> wait(double seconds) {
    const auto deadline = SteadyClock::now() + std::chrono::duration<double>(seconds);
    while (!status_) {
      int raw = 0;
      const pid_t r = ::waitpid(pid_, &raw, WNOHANG);
      if (r == pid_) {
        status_ = WIFEXITED(raw) ? WEXITSTATUS(raw) : 128 + WTERMSIG(raw);
      } else if (r < 0) {
        status_ = -1;
      } else if (SteadyClock::now() >= deadline) {
        break;
      } else {
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
      }
    }
    return status_;
  }

  // SIGTERM, a grace period, SIGKILL. Returns the exit status.
  int stop(double grace_s = 5.0) {
    if (pid_ <= 0) return -1;
    if (!status_) {
      ::kill(pid_, SIGTERM);
      if (!wait(grace_s)) {
        ::kill(pid_, SIGKILL);
        wait(60.0);
      }
    }
    return status_.value_or(-1);
  }

 private:
  pid_t pid_ = -1;
  fs::path log_;
  std::optional<int> status_;
};

// Runs the swa_sim command line `sim_args` with --export-agent-config <dir>/agent.yaml (its output in
// <dir>/export.log): the agents' configuration of that scenario. Its exit status, nullopt if it ran for 30 s.
inline std::optional<int> exportAgentConfig(std::vector<std::string> sim_args, const fs::path& dir) {
  sim_args.insert(sim_args.end(), {"--export-agent-config", (dir / "agent.yaml").string()});
  Child exporter(sim_args, dir / "export.log");
  return exporter.wait(30.0);
}

// The launcher's janitor (deploy/programs/launch/shm_janitor.h: removes only abandoned Fast DDS files created after
// construction), which in a test also cleans up when it goes out of scope, so a failing check leaves nothing behind.
class ShmJanitor : public launch::ShmJanitor {
 public:
  ShmJanitor() = default;
  ~ShmJanitor() { clean(); }
  ShmJanitor(const ShmJanitor&) = delete;
  ShmJanitor& operator=(const ShmJanitor&) = delete;
};

// Of the shared-memory file names `files`, those that can be a test's on DDS domain `domain`: the ports of that domain
// (Fast DDS numbers them 7400 + 250 domain + 0..249; files fastrtps_port<N>, its _el/_sl locks and its
// sem.fastrtps_port<N>_mutex) and the segments, which carry no domain. Tests run two at a time, and the ports of
// another test's processes stay in /dev/shm for a moment after they exit, until the last peer that wrote to them
// closes them.
inline std::vector<std::string> ofDomain(const std::vector<std::string>& files, int domain) {
  std::vector<std::string> out;
  for (const std::string& f : files) {
    const std::size_t at = f.find("fastrtps_port");
    if (at != std::string::npos) {
      const std::size_t digits = at + std::string("fastrtps_port").size();
      const std::size_t end = f.find_first_not_of("0123456789", digits);
      if (end != digits) {
        const long port = std::stol(f.substr(digits, end - digits));
        const swa::dds::PortMapping ports;  // the mapping every SWA participant uses
        if (port < ports.base || (port - ports.base) / ports.domain_gain != domain) continue;
      }
    }
    out.push_back(f);
  }
  return out;
}

// The abandoned shared-memory files `janitor` finds that can be those of a test on `domain` (ofDomain): "" when there
// are none, else how many and the first.
inline std::string shmFilesLeft(const launch::ShmJanitor& janitor, int domain) {
  const std::vector<std::string> left = ofDomain(janitor.zombies(), domain);
  if (left.empty()) return "";
  return std::to_string(left.size()) + " /dev/shm file(s), first " + left.front();
}

// A DDS domain of our own: from the PID (Fast DDS's own tests do the same), never 0, at most 232, reserved. Throws
// (the test fails saying why) when other SWA tests hold all of them.
inline int testDomain(int offset = 0) {
  const int domain = reserveTestDomain(1 + static_cast<int>((::getpid() + offset) % 200));
  if (domain < 0) {
    throw std::runtime_error("no free DDS domain: other SWA tests hold all 232 (/tmp/swa-test-domain-<d>.lock)");
  }
  return domain;
}

// A swarm of our own (SWA_SWARM, a DDS partition): set in this process's environment, so this test's participants
// and every child it starts (the launcher too) share it, and another DDS user that happens to be on the same domain
// (two CI jobs, another developer's swarm) never exchanges a sample with the test. Unique per call.
inline std::string useOwnSwarm() {
  static int count = 0;
  const std::string name = "test-" + std::to_string(::getpid()) + "-" + std::to_string(++count);
  ::setenv("SWA_SWARM", name.c_str(), 1);
  return name;
}

}  // namespace swa::testing

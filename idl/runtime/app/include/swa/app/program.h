#pragma once
// The one shape of every SWA program (after the Fast DDS Application example): a process role is a class with
// run() and stop(); main() is runProgram(). Everything that can be wrong with the command line and the files it names
// is found before any DDS entity exists (exit 2, nothing started); then the role runs until it is done or SIGINT /
// SIGTERM asks it to stop (the handler only sets a flag; a watcher thread calls Role::stop), and a failure to start
// (a DDS error, refused credentials) has the role's start status.
// A program's prepare() lives inside namespace swa: Fast DDS declares a global `namespace dds =
// eprosima::fastdds::dds;`, and only there does `dds::` name ours.

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace swa::app {

class Role {
 public:
  virtual ~Role() = default;
  // Runs to the end (or until stop()); returns the process exit status.
  virtual int run() = 0;
  // Thread-safe; run() returns soon after. Also what SIGINT / SIGTERM do.
  virtual void stop() = 0;
};

// What a program decided from its command line: exit now (--help, a listing, an export), or start a role.
struct Plan {
  std::optional<int> exit_now;
  // Creates the role (and its DDS entities); may throw, which exits with `start_failure_status`.
  std::function<std::unique_ptr<Role>()> start;
  int start_failure_status = 1;
};

inline Plan exitWith(int status) { return Plan{status, nullptr, 1}; }

// Start the role `start` makes; a failure to start exits with `failure_status`.
inline Plan startWith(std::function<std::unique_ptr<Role>()> start, int failure_status = 1) {
  return Plan{std::nullopt, std::move(start), failure_status};
}

// --help, --parameters: when `asked`, prints what `text` makes to stdout and the program exits 0.
std::optional<Plan> printIf(bool asked, const std::function<std::string()>& text);
// The same for a program with both: --help first, then the listing of its parameters.
std::optional<Plan> printIf(bool help, const std::function<std::string()>& usage, bool list_parameters,
                            const std::function<std::string()>& parameters);

// `name` prefixes every message ("swa_sim: ..."); `input` names what a params::ConfigError is about ("scenario",
// "configuration"). `prepare` reads the arguments and the files they name, and throws on any problem: exit 2 with
// the message (every problem of a file at once) and a pointer to --help.
int runProgram(const std::string& name, const std::string& input, int argc, char** argv,
               const std::function<Plan(const std::vector<std::string>& args)>& prepare);

}  // namespace swa::app

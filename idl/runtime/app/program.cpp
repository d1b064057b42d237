#include "swa/app/program.h"

#include <atomic>
#include <cstdio>
#include <exception>
#include <thread>

#include "swa/app/signals.h"
#include "swa/params/error.h"

namespace swa::app {

std::optional<Plan> printIf(bool asked, const std::function<std::string()>& text) {
  if (!asked) return std::nullopt;
  std::fputs(text().c_str(), stdout);
  return exitWith(0);
}

std::optional<Plan> printIf(bool help, const std::function<std::string()>& usage, bool list_parameters,
                            const std::function<std::string()>& parameters) {
  if (auto done = printIf(help, usage)) return done;
  return printIf(list_parameters, parameters);
}

int runProgram(const std::string& name, const std::string& input, int argc, char** argv,
               const std::function<Plan(const std::vector<std::string>& args)>& prepare) {
  Plan plan;
  try {
    plan = prepare(std::vector<std::string>(argv + 1, argv + argc));
  } catch (const params::ConfigError& e) {
    std::fprintf(stderr, "%s: invalid %s:\n%s\n", name.c_str(), input.c_str(), e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n(see %s --help)\n", name.c_str(), e.what(), name.c_str());
    return 2;
  }
  if (plan.exit_now) return *plan.exit_now;

  installShutdownHandlers();
  std::unique_ptr<Role> role;
  try {
    role = plan.start();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", name.c_str(), e.what());
    return plan.start_failure_status;
  }
  // The handler cannot call into the role; this thread (created while the signals are still blocked, so they never
  // land in it) turns the flag into stop().
  std::atomic<bool> done{false};
  std::thread watcher([&] {
    while (true) {
      awaitShutdownOrWake();
      if (done.load()) return;
      if (shutdownRequested()) {
        role->stop();
        return;
      }
    }
  });
  acceptShutdownSignals();
  int status = 1;
  try {
    status = role->run();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", name.c_str(), e.what());
  }
  done.store(true);
  wakeShutdownWatcher();
  watcher.join();
  return status;
}

}  // namespace swa::app

#pragma once
// What the tests that run swa_launch share: the pid of one of its children (found by the --domain on its command
// line), and a watch on an agent's published state to time what a test does to a run (kill a process at a given
// simulation time).

#include <signal.h>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <thread>

#include <swa/msg/AgentStatePubSubTypes.h>

#include "process_support.h"
#include "swa/dds/options.h"
#include "swa/dds/participant.h"
#include "swa/dds/qos_profiles.h"
#include "swa/dds/topics.h"

namespace swa::testing {

// The pid of the process `program` (swa_agent, swa_px4_bridge) for `uav` on `domain`, or -1.
inline int uavProcessPid(int domain, const std::string& program, int uav) {
  const std::string id = std::string("--id") + '\0' + std::to_string(uav) + '\0';
  for (int pid : processesOnDomain(domain)) {
    const std::string cmdline = readFile(fs::path("/proc") / std::to_string(pid) / "cmdline");
    if (cmdline.find(program) != std::string::npos && cmdline.find(id) != std::string::npos) return pid;
  }
  return -1;
}

inline int agentPid(int domain, int uav) { return uavProcessPid(domain, "swa_agent", uav); }

inline int monitorPid(int domain) {
  for (int pid : processesOnDomain(domain)) {
    const std::string cmdline = readFile(fs::path("/proc") / std::to_string(pid) / "cmdline");
    if (cmdline.find("swa_monitor") != std::string::npos) return pid;
  }
  return -1;
}

// Only to time what a test does to a run: a participant of the test that keeps the newest stamp agent `uav` has
// published its state for.
class StateStampWatch {
 public:
  StateStampWatch(int domain, int uav)
      : participant_(std::make_unique<dds::Participant>("swa_test_observer", domain, dds::resolveProfilesFile())) {
    participant_->reader<msg::AgentStatePubSubType>(dds::topics::state(uav), dds::qos::kStateReader,
                                                    [this](msg::AgentState&& s) {
                                                      newest_ns_.store(s.header().stamp_ns());
                                                      // A new agent process numbers its states from 1 again.
                                                      if (s.header().seq() <= last_seq_) ++new_processes_;
                                                      last_seq_ = s.header().seq();
                                                    });
  }

  // How often the states started again from a new agent process.
  int newProcessesHeard() const { return new_processes_.load(); }

  // Waits until that stamp reaches `at_ns`, polling every 5 ms, for 60 s at most and only while `launch` runs.
  // Whether it did.
  bool waitUntil(long long at_ns, Child& launch) const {
    const auto deadline = SteadyClock::now() + std::chrono::seconds(60);
    while (newest_ns_.load() < at_ns && SteadyClock::now() < deadline && !launch.wait(0.0)) {
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    return newest_ns_.load() >= at_ns;
  }

  // Once that stamp reaches `at_ns` (see waitUntil), SIGKILLs the process `victim` names. The pid killed; -1 when the
  // stamp never got there, and what `victim` gave (<= 0) when it found no process.
  int killWhenReached(long long at_ns, Child& launch, const std::function<int()>& victim) const {
    if (!waitUntil(at_ns, launch)) return -1;
    const int pid = victim();
    if (pid > 0) ::kill(pid, SIGKILL);
    return pid;
  }

 private:
  // Declared first: they outlive the participant whose listener writes them.
  std::atomic<long long> newest_ns_{0};
  std::uint32_t last_seq_ = 0;  // the listener's only
  std::atomic<int> new_processes_{0};
  std::unique_ptr<dds::Participant> participant_;
};

}  // namespace swa::testing

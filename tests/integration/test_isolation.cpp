// No inter-agent communication, enforced and proven (DESIGN §1): an observer participant in this test collects,
// through Fast DDS discovery (DomainParticipantListener on_participant_discovery / on_subscriber_discovery /
// on_publisher_discovery), every reader and writer of every participant during a swa_sim + 4 swa_agent run on a
// private domain, and the run fails if any agent reads a topic another agent writes or anything outside its own
// swa/uav<I>/ namespace and the clock (isolation_audit.h). Every child is reaped and every shared-memory file a
// killed process leaves is removed on the way out, also when a check fails.

#include <signal.h>

#include <algorithm>
#include <chrono>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include <swa/msg/AgentStatePubSubTypes.h>
#include <swa/msg/SwarmTruthPubSubTypes.h>

#include "discovery_observer.h"
#include "isolation_audit.h"
#include "process_test.h"
#include "swa/dds/options.h"
#include "swa/dds/participant.h"
#include "swa/dds/qos_profiles.h"
#include "swa/dds/topics.h"

namespace swa::testing {
namespace {

const std::string kScenario = std::string(SWA_SOURCE_DIR) + "/deploy/scenarios/dropout_4.yaml";
constexpr int kAgents = 4;
constexpr double kRunBoundS = 40.0;       // wall-clock bound of the simulator run (measured: 0.6 to 2.5 s)
constexpr double kLateDiscoveryS = 10.0;  // longest wait for discovery to reach the observer

bool has(const std::vector<Endpoint>& endpoints, const std::string& participant, EndpointKind kind,
         const std::string& topic) {
  return std::any_of(endpoints.begin(), endpoints.end(), [&](const Endpoint& e) {
    return e.participant == participant && e.kind == kind && e.topic == topic;
  });
}

// Whether swa_sim's per-UAV endpoints of this run's agents have all been discovered.
bool simEndpointsSeen(const std::vector<Endpoint>& endpoints) {
  for (int i = 0; i < kAgents; ++i) {
    // The simulator writes each UAV's samples in frames (SWA naming), the three topics otherwise.
    const bool frames = has(endpoints, "swa_sim", EndpointKind::kWriter, dds::topics::sensors(i));
    for (const std::string& topic : {dds::topics::imu(i), dds::topics::detections(i), dds::topics::gnss(i)}) {
      if (!frames && !has(endpoints, "swa_sim", EndpointKind::kWriter, topic)) return false;
    }
    if (!has(endpoints, "swa_sim", EndpointKind::kReader, dds::topics::cmdVel(i))) return false;
  }
  return true;
}

std::string bulleted(const std::vector<std::string>& lines) {
  std::string s;
  for (const std::string& l : lines) s += "  " + l + "\n";
  return s;
}

class IsolationRun : public ProcessRun {
 protected:
  void SetUp() override {
    dir_ = freshTestDir("swa_isolation_it");
    observer_ = observeQuietDomain(domain_, "swa_test_isolation_observer");
    ASSERT_TRUE(observer_) << "no quiet DDS domain found";
  }

  void stopObservers() override { observer_.reset(); }

  std::vector<std::string> simArgs() const {
    return {SWA_SIM_BINARY, "--scenario", kScenario, "--set", "duration_s=10"};
  }

  std::string logs() const { return runLogs(dir_, static_cast<std::size_t>(kAgents)); }

  std::unique_ptr<DiscoveryObserver> observer_;
};

TEST_F(IsolationRun, NoAgentReadsWhatAnotherAgentWritesOrAnythingOutsideItsNamespace) {
  // GIVEN the observer listening on a private domain, and the agents' configuration exported from the scenario
  ASSERT_EQ(exportAgentConfig(simArgs(), dir_), 0) << readFile(dir_ / "export.log");

  // WHEN swa_sim and 4 swa_agent processes run the GNSS-loss scenario for 10 s of simulated time (lockstep). The
  // simulator starts first and waits for the agents; the agents start once the observer has discovered the
  // simulator's endpoints (a lockstep run takes well under a second, and the simulator waits for its own view of
  // the agents, not for ours)
  const auto started = SteadyClock::now();
  std::vector<std::string> args = simArgs();
  args.insert(args.end(), {"--domain", std::to_string(domain_), "--startup-timeout-s", "20", "--agent-timeout-s", "10",
                           "--summary-out", (dir_ / "summary.json").string()});
  sim_ = std::make_unique<Child>(args, dir_ / "sim.log");
  const bool sim_seen = waitFor([&] { return simEndpointsSeen(observer_->log().endpoints()); }, kLateDiscoveryS);
  for (int i = 0; i < kAgents; ++i) {
    agents_.push_back(std::make_unique<Child>(agentCommand(SWA_AGENT_BINARY, i, domain_, dir_ / "agent.yaml"),
                                              dir_ / ("agent" + std::to_string(i) + ".log")));
  }
  // ... and the observer collects until the simulator exits, then (bounded) until it has every agent endpoint,
  // then until the agents exit
  const std::optional<int> sim_status = sim_->wait(kRunBoundS);
  const double wall_s = std::chrono::duration<double>(SteadyClock::now() - started).count();
  waitFor([&] { return auditAgentEndpoints(observer_->log().endpoints(), kAgents).empty(); }, kLateDiscoveryS);
  for (auto& a : agents_) a->signal(SIGTERM);  // together, so their clean shutdowns overlap
  std::vector<int> agent_status;
  for (auto& a : agents_) agent_status.push_back(a->stop(10.0));
  const std::vector<Endpoint> endpoints = observer_->log().endpoints();

  const std::string table = endpointTable(endpoints);
  std::cout << "domain " << domain_ << ", " << wall_s << " s wall (processes started to sim exit), " << endpoints.size()
            << " endpoints discovered:\n"
            << table;
  RecordProperty("wall_s", std::to_string(wall_s));

  // THEN the run itself was a normal one: the simulator completed and every agent shut down cleanly
  ASSERT_TRUE(sim_status) << "swa_sim still running after " << kRunBoundS << " s: killed\n" << logs();
  EXPECT_EQ(*sim_status, 0) << logs();
  for (int i = 0; i < kAgents; ++i) EXPECT_EQ(agent_status[i], 0) << "agent " << i << "\n" << logs();

  // THEN discovery saw the whole system, so the audit below cannot pass on too little: each agent 0..3 exactly once
  // with exactly its five endpoints, and the simulator with its endpoints
  const std::vector<std::string> missing = auditAgentEndpoints(endpoints, kAgents);
  EXPECT_TRUE(missing.empty()) << "incomplete or unexpected agent endpoints:\n"
                               << bulleted(missing) << "collected:\n"
                               << table;
  EXPECT_TRUE(sim_seen && simEndpointsSeen(endpoints)) << "swa_sim's endpoints not all discovered; collected:\n"
                                                       << table;

  // THEN no agent reads a topic another agent writes, nor anything outside swa/uav<I>/ but the clock, nor truth
  const std::vector<std::string> violations = auditIsolation(endpoints);
  EXPECT_TRUE(violations.empty()) << "isolation violated:\n" << bulleted(violations) << "collected:\n" << table;

  // THEN, once the observer is gone too, no process left shared memory behind
  observer_.reset();
  const std::string left = shmFilesLeft(janitor_, domain_);
  EXPECT_TRUE(left.empty()) << "a process exited without deleting its DDS entities: " << left;
}

}  // namespace
}  // namespace swa::testing

namespace swa::testing {
namespace {

TEST_F(IsolationRun, AuditCatchesARogueParticipantReadingAnotherAgentsOutput) {
  // GIVEN agent 2 running, and in this process a rogue participant that calls itself swa_agent_1 and reads agent 2's
  // state and the ground truth (real readers: they match agent 2's and anyone's writers)
  agents_.push_back(std::make_unique<Child>(agentCommand(SWA_AGENT_BINARY, 2, domain_), dir_ / "agent2.log"));
  auto rogue = std::make_unique<dds::Participant>("swa_agent_1", domain_, dds::resolveProfilesFile());
  rogue->reader<msg::AgentStatePubSubType>(dds::topics::state(2), dds::qos::kStateReader, [](msg::AgentState&&) {});
  rogue->reader<msg::SwarmTruthPubSubType>(dds::topics::kTruth, dds::qos::kTruthReader, [](msg::SwarmTruth&&) {});
  // WHEN the observer has discovered both: every endpoint of agent 2 (its writer alone was once seen before its
  // readers, on a loaded host, and the completeness check below then named agent 2), and the rogue's readers
  const bool seen = waitFor(
      [&] {
        const std::vector<Endpoint> e = observer_->log().endpoints();
        const std::string missing = bulleted(auditAgentEndpoints(e, 3));
        return missing.find("swa_agent_2") == std::string::npos &&
               has(e, "swa_agent_2", EndpointKind::kWriter, dds::topics::state(2)) &&
               has(e, "swa_agent_1", EndpointKind::kReader, dds::topics::state(2)) &&
               has(e, "swa_agent_1", EndpointKind::kReader, dds::topics::kTruth);
      },
      kLateDiscoveryS);
  const std::vector<Endpoint> endpoints = observer_->log().endpoints();
  const std::string table = endpointTable(endpoints);
  ASSERT_TRUE(seen) << "collected:\n" << table << logs();
  // THEN the audit names each breach of the rogue, and nothing of agent 2
  const std::vector<std::string> v = auditIsolation(endpoints);
  const auto reported = [&](const std::vector<std::string>& needles) {
    return std::any_of(v.begin(), v.end(), [&](const std::string& line) {
      return std::all_of(needles.begin(), needles.end(),
                         [&](const std::string& n) { return line.find(n) != std::string::npos; });
    });
  };
  EXPECT_TRUE(reported({"swa_agent_1", "reads swa/uav2/state", "which agent swa_agent_2"})) << bulleted(v) << table;
  EXPECT_TRUE(reported({"swa_agent_1", "reads swa/uav2/state", "outside its own namespace swa/uav1/"}))
      << bulleted(v) << table;
  EXPECT_TRUE(reported({"swa_agent_1", "reads swa/truth", "ground truth"})) << bulleted(v) << table;
  EXPECT_EQ(v.size(), 3u) << bulleted(v) << table;
  // THEN the completeness check finds the rogue's missing endpoints (and the agents that never ran)
  const std::vector<std::string> c = auditAgentEndpoints(endpoints, 3);
  EXPECT_NE(bulleted(c).find("swa_agent_1 has no reader on swa/uav1/imu"), std::string::npos) << bulleted(c);
  EXPECT_NE(bulleted(c).find("swa_agent_0 was never discovered"), std::string::npos) << bulleted(c);
  EXPECT_EQ(bulleted(c).find("swa_agent_2"), std::string::npos) << bulleted(c);
  rogue.reset();
}

}  // namespace
}  // namespace swa::testing

#pragma once
// Shared by the fuzz tests (test_rogue_input.cpp, test_rogue_detections.cpp): one swa_agent on a private domain and
// swarm, and a rogue DDS participant beside it that writes the agent's IMU and reads its commands. Each test adds
// the writers of what it attacks.

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <memory>
#include <string>

#include <swa/msg/ImuPubSubTypes.h>
#include <swa/msg/VelocitySetpointPubSubTypes.h>

#include "process_test.h"
#include "swa/agent/samples.h"
#include "swa/dds/options.h"
#include "swa/dds/participant.h"
#include "swa/dds/qos_profiles.h"
#include "swa/dds/topics.h"

namespace swa::testing {

class RogueAgentTest : public ::testing::Test {
 protected:
  // Starts the agent of UAV `uav` (with `config` if given) in a fresh directory named after `dir_prefix`, on the test
  // domain of `domain_slot` and a swarm of its own, and the rogue with its IMU writer and command reader.
  void startAgentAndRogue(const std::string& dir_prefix, bool dir_per_test, int domain_slot, int uav,
                          const std::string& config_yaml = {}) {
    dir_ = freshTestDir(dir_prefix, dir_per_test);
    domain_ = testDomain(domain_slot);
    useOwnSwarm();
    fs::path config;
    if (!config_yaml.empty()) {
      config = dir_ / "agent.yaml";
      std::ofstream(config) << config_yaml;
    }
    agent_ = std::make_unique<Child>(agentCommand(SWA_AGENT_BINARY, uav, domain_, config), dir_ / "agent.log");
    rogue_ = std::make_unique<dds::Participant>("swa_test_rogue", domain_, dds::resolveProfilesFile());
    imu_ = rogue_->writer<msg::ImuPubSubType>(dds::topics::imu(uav), dds::qos::kSensorWriter);
    rogue_->reader<msg::VelocitySetpointPubSubType>(dds::topics::cmdVel(uav), dds::qos::kCommandReader,
                                                    cmds_.listener());
  }

  void TearDown() override {
    agent_.reset();
    rogue_.reset();
    janitor_.clean();
    if (!HasFailure()) fs::remove_all(dir_);
  }

  OwnShm own_shm_;  // first: this test's /dev/shm is its own (private_shm.h)
  fs::path dir_;
  int domain_ = 0;
  ShmJanitor janitor_;
  std::unique_ptr<Child> agent_;
  Received<msg::VelocitySetpoint> cmds_;
  std::unique_ptr<dds::Participant> rogue_;
  dds::Writer<msg::Imu> imu_;
};

// Neighbour `j` (0, 1, 2) of the genuine detections both tests send: on a ring of 10 m around a point 1 m ahead of the
// UAV, in its body frame, with UAV id 10 + j.
inline agent::Vec2 ringNeighbour(int j) { return {10.0 * std::cos(2.1 * j) + 1.0, 10.0 * std::sin(2.1 * j)}; }
inline int ringNeighbourId(int j) { return 10 + j; }

}  // namespace swa::testing

// The isolation audit of test_isolation on synthetic endpoint lists: a clean swarm passes, and every kind of breach
// (reading another UAV's topic, reading what another agent writes, writing outside the own namespace, reading
// ground truth, an incomplete or duplicated agent) is reported, so the integration test can fail.

#include <algorithm>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "isolation_audit.h"
#include "swa/dds/topics.h"
#include "swa/px4/release.h"

namespace swa::testing {
namespace {

namespace topics = dds::topics;
constexpr EndpointKind kR = EndpointKind::kReader;
constexpr EndpointKind kW = EndpointKind::kWriter;

std::string guidOf(const std::string& participant) { return "guid-" + participant; }

Endpoint ep(EndpointKind kind, const std::string& participant, const std::string& topic) {
  return Endpoint{kind, participant, guidOf(participant), topic, "T"};
}

// What the shipped processes create: swa_sim with every sensor writer and command reader plus truth / events /
// clock, a monitor reading truth, events and states, the ground writing the mission, and `n` agents with their six
// endpoints (the mission read by each).
std::vector<Endpoint> cleanSwarm(int n) {
  std::vector<Endpoint> e;
  for (const char* t : {topics::kTruth, topics::kEvents, topics::kClock}) e.push_back(ep(kW, "swa_sim", t));
  e.push_back(ep(kR, "swa_monitor", topics::kTruth));
  e.push_back(ep(kR, "swa_monitor", topics::kEvents));
  e.push_back(ep(kW, "swa_ground", topics::kMission));
  for (int i = 0; i < n; ++i) {
    const std::string agent = "swa_agent_" + std::to_string(i);
    e.push_back(ep(kR, agent, topics::kMission));
    for (const std::string& t : {topics::imu(i), topics::detections(i), topics::gnss(i)}) {
      e.push_back(ep(kW, "swa_sim", t));
      e.push_back(ep(kR, agent, t));
    }
    e.push_back(ep(kR, "swa_sim", topics::cmdVel(i)));
    e.push_back(ep(kW, agent, topics::cmdVel(i)));
    e.push_back(ep(kW, agent, topics::state(i)));
    e.push_back(ep(kR, "swa_monitor", topics::state(i)));
  }
  return e;
}

bool mentions(const std::vector<std::string>& lines, const std::vector<std::string>& needles) {
  return std::any_of(lines.begin(), lines.end(), [&](const std::string& line) {
    return std::all_of(needles.begin(), needles.end(),
                       [&](const std::string& n) { return line.find(n) != std::string::npos; });
  });
}

std::string joined(const std::vector<std::string>& lines) {
  std::string s;
  for (const std::string& l : lines) s += l + "\n";
  return s;
}

TEST(IsolationAudit, AgentIndexAcceptsOnlyCanonicalAgentNames) {
  EXPECT_EQ(agentIndex("swa_agent_0"), 0);
  EXPECT_EQ(agentIndex("swa_agent_17"), 17);
  for (const char* name :
       {"swa_agent_", "swa_agent_01", "swa_agent_-1", "swa_agent_1x", "swa_sim", "agent_1", "swa_agent_1234567", ""}) {
    EXPECT_FALSE(agentIndex(name)) << name;
  }
}

TEST(IsolationAudit, CleanSwarmHasNoViolationAndIsComplete) {
  const std::vector<Endpoint> e = cleanSwarm(4);
  EXPECT_TRUE(auditIsolation(e).empty()) << joined(auditIsolation(e));
  EXPECT_TRUE(auditAgentEndpoints(e, 4).empty()) << joined(auditAgentEndpoints(e, 4));
}

TEST(IsolationAudit, ReadingTheClockIsAllowed) {
  std::vector<Endpoint> e = cleanSwarm(2);
  e.push_back(ep(kR, "swa_agent_1", topics::kClock));
  EXPECT_TRUE(auditIsolation(e).empty()) << joined(auditIsolation(e));
  EXPECT_TRUE(auditAgentEndpoints(e, 2).empty()) << joined(auditAgentEndpoints(e, 2));
}

TEST(IsolationAudit, AnAgentWritingTheGroundsMissionIsReportedAndSoIsEveryAgentReadingIt) {
  // GIVEN a clean swarm in which agent 2 also writes the mission every agent reads (issue #45: the ground's only)
  std::vector<Endpoint> e = cleanSwarm(4);
  e.push_back(ep(kW, "swa_agent_2", topics::kMission));
  const std::vector<std::string> v = auditIsolation(e);
  // THEN its writer is outside its namespace, and the three other agents read what an agent writes
  EXPECT_TRUE(mentions(v, {"swa_agent_2", "writes swa/swarm/mission", "outside its own namespace"})) << joined(v);
  for (const char* reader : {"swa_agent_0", "swa_agent_1", "swa_agent_3"}) {
    EXPECT_TRUE(mentions(v, {reader, "reads swa/swarm/mission", "which agent swa_agent_2"})) << joined(v);
  }
  EXPECT_EQ(v.size(), 4u) << joined(v);
}

TEST(IsolationAudit, PlantedViolationsAreEachReported) {
  // GIVEN a clean swarm with three planted breaches
  std::vector<Endpoint> e = cleanSwarm(4);
  e.push_back(ep(kR, "swa_agent_1", topics::imu(2)));    // another UAV's sensors (written by the simulator)
  e.push_back(ep(kW, "swa_agent_0", topics::kTruth));    // writing outside its namespace
  e.push_back(ep(kR, "swa_agent_3", topics::state(2)));  // what another agent writes
  // WHEN audited
  const std::vector<std::string> v = auditIsolation(e);
  // THEN each breach is named, with the participant and the topic
  EXPECT_TRUE(mentions(v, {"swa_agent_1", "reads swa/uav2/imu", "outside its own namespace swa/uav1/"})) << joined(v);
  EXPECT_TRUE(mentions(v, {"swa_agent_0", "writes swa/truth", "outside its own namespace swa/uav0/"})) << joined(v);
  EXPECT_TRUE(mentions(v, {"swa_agent_3", "reads swa/uav2/state", "outside"})) << joined(v);
  EXPECT_TRUE(mentions(v, {"swa_agent_3", "reads swa/uav2/state", "which agent swa_agent_2"})) << joined(v);
  EXPECT_EQ(v.size(), 4u) << joined(v);
  // THEN the completeness check reports the extra endpoints as unexpected
  const std::vector<std::string> c = auditAgentEndpoints(e, 4);
  EXPECT_TRUE(mentions(c, {"swa_agent_1", "unexpected reader on swa/uav2/imu"})) << joined(c);
  EXPECT_TRUE(mentions(c, {"swa_agent_0", "unexpected writer on swa/truth"})) << joined(c);
  EXPECT_TRUE(mentions(c, {"swa_agent_3", "unexpected reader on swa/uav2/state"})) << joined(c);
  EXPECT_EQ(c.size(), 3u) << joined(c);
}

TEST(IsolationAudit, ReadingGroundTruthIsReported) {
  std::vector<Endpoint> e = cleanSwarm(2);
  e.push_back(ep(kR, "swa_agent_1", topics::kTruth));
  const std::vector<std::string> v = auditIsolation(e);
  ASSERT_EQ(v.size(), 1u) << joined(v);
  EXPECT_TRUE(mentions(v, {"swa_agent_1", "reads swa/truth", "ground truth"})) << joined(v);
}

TEST(IsolationAudit, ReadingATopicAnotherAgentWritesIsReportedEvenInsideTheOwnNamespace) {
  // GIVEN agent 2 writes into agent 1's namespace, which agent 1 reads
  std::vector<Endpoint> e = cleanSwarm(3);
  e.push_back(ep(kW, "swa_agent_2", topics::imu(1)));
  const std::vector<std::string> v = auditIsolation(e);
  // THEN both sides are reported: the writer is outside its namespace, the reader reads another agent
  EXPECT_TRUE(mentions(v, {"swa_agent_2", "writes swa/uav1/imu", "outside"})) << joined(v);
  EXPECT_TRUE(mentions(v, {"swa_agent_1", "reads swa/uav1/imu", "which agent swa_agent_2"})) << joined(v);
  EXPECT_EQ(v.size(), 2u) << joined(v);
}

TEST(IsolationAudit, WritingTheClockIsReported) {
  std::vector<Endpoint> e = cleanSwarm(2);
  e.push_back(ep(kW, "swa_agent_0", topics::kClock));
  e.push_back(ep(kR, "swa_agent_1", topics::kClock));
  const std::vector<std::string> v = auditIsolation(e);
  EXPECT_TRUE(mentions(v, {"swa_agent_0", "writes swa/clock"})) << joined(v);
  EXPECT_TRUE(mentions(v, {"swa_agent_1", "reads swa/clock", "which agent swa_agent_0"})) << joined(v);
  EXPECT_EQ(v.size(), 2u) << joined(v);
}

TEST(IsolationAudit, TwoParticipantsWithOneAgentNameAreAuditedAgainstEachOther) {
  // GIVEN an impostor also named swa_agent_1 (another GUID prefix) that writes agent 1's sensor topic
  std::vector<Endpoint> e = cleanSwarm(2);
  e.push_back(Endpoint{kW, "swa_agent_1", "guid-impostor", topics::gnss(1), "T"});
  // THEN the real agent 1 reads what another agent participant writes, and agent 1 is not one participant
  EXPECT_TRUE(mentions(auditIsolation(e), {"swa_agent_1 [guid-swa_agent_1]", "reads swa/uav1/gnss",
                                           "which agent swa_agent_1 [guid-impostor]"}))
      << joined(auditIsolation(e));
  EXPECT_TRUE(mentions(auditAgentEndpoints(e, 2), {"2 participants are named swa_agent_1"}))
      << joined(auditAgentEndpoints(e, 2));
}

TEST(IsolationAudit, UnnamedAndMisnamedParticipantsCannotBeCleared) {
  std::vector<Endpoint> e = cleanSwarm(1);
  e.push_back(Endpoint{kR, "", "guid-x", topics::imu(0), "T"});
  e.push_back(Endpoint{kR, "swa_agent_01", "guid-y", topics::imu(0), "T"});
  const std::vector<std::string> v = auditIsolation(e);
  EXPECT_TRUE(mentions(v, {"[guid-x]", "never announced its name"})) << joined(v);
  EXPECT_TRUE(mentions(v, {"swa_agent_01", "not swa_agent_<I>"})) << joined(v);
  EXPECT_EQ(v.size(), 2u) << joined(v);
}

TEST(IsolationAudit, IncompleteOrExtraAgentsAreReported) {
  // GIVEN 3 agents expected, agent 1 without its state writer, agent 2 missing, an agent 5 present, agent 0 with
  // two IMU readers
  std::vector<Endpoint> e = cleanSwarm(2);
  e.erase(
      std::remove_if(e.begin(), e.end(),
                     [](const Endpoint& x) { return x.participant == "swa_agent_1" && x.topic == topics::state(1); }),
      e.end());
  e.push_back(ep(kR, "swa_agent_5", topics::imu(5)));
  e.push_back(ep(kR, "swa_agent_0", topics::imu(0)));
  const std::vector<std::string> c = auditAgentEndpoints(e, 3);
  EXPECT_TRUE(mentions(c, {"swa_agent_1 has no writer on swa/uav1/state"})) << joined(c);
  EXPECT_TRUE(mentions(c, {"swa_agent_2 was never discovered"})) << joined(c);
  EXPECT_TRUE(mentions(c, {"swa_agent_5 is not one of the 3 agents"})) << joined(c);
  EXPECT_TRUE(mentions(c, {"swa_agent_0 has 2 readers on swa/uav0/imu"})) << joined(c);
  EXPECT_EQ(c.size(), 4u) << joined(c);
  // THEN the isolation rules themselves still hold for these endpoints
  EXPECT_TRUE(auditIsolation(e).empty()) << joined(auditIsolation(e));
}

TEST(IsolationAudit, NothingDiscoveredIsIncomplete) {
  EXPECT_TRUE(auditIsolation({}).empty());
  EXPECT_EQ(auditAgentEndpoints({}, 4).size(), 4u);
}

// The same swarm through PX4 (swa_launch --vehicle px4): the simulator plays the autopilots, one bridge per UAV.
std::vector<Endpoint> px4Swarm(int n) {
  std::vector<Endpoint> e = cleanSwarm(n);
  for (int i = 0; i < n; ++i) {
    const std::string bridge = "swa_bridge_" + std::to_string(i);
    const std::string ns = topics::px4Namespace(i);
    // The stand-ins play the newest release by default: vehicle_status_v1.
    const std::string status = px4::topicName(px4::kNewestRelease, "vehicle_status");
    for (const std::string& t : {std::string("vehicle_attitude"), status, std::string("vehicle_command_ack")}) {
      e.push_back(ep(kW, "swa_sim", topics::px4Out(ns, t)));
      e.push_back(ep(kR, bridge, topics::px4Out(ns, t)));
    }
    for (const char* t : {"trajectory_setpoint", "offboard_control_mode", "vehicle_command"}) {
      e.push_back(ep(kR, "swa_sim", topics::px4In(ns, t)));
      e.push_back(ep(kW, bridge, topics::px4In(ns, t)));
    }
    e.push_back(ep(kW, bridge, topics::imu(i)));
    e.push_back(ep(kR, bridge, topics::cmdVel(i)));
    e.push_back(ep(kW, bridge, topics::bridgeState(i)));
  }
  return e;
}

TEST(IsolationAudit, BridgesTouchOnlyTheirOwnVehicleAndUav) {
  // GIVEN what a run through PX4 creates THEN the bridges pass, and the agents' rules still hold
  const std::vector<Endpoint> clean = px4Swarm(3);
  const std::vector<std::string> none = auditBridges(clean, 3, px4Topics(topics::px4Namespace));
  EXPECT_TRUE(none.empty()) << joined(none);
  EXPECT_TRUE(auditIsolation(clean).empty()) << joined(auditIsolation(clean));
  // WHEN bridge 1 reads vehicle 2's attitude and writes UAV 2's IMU, agent 0 reads its vehicle's attitude itself,
  // bridge 2 is missing its setpoint writer, and a second participant calls itself swa_bridge_0
  std::vector<Endpoint> e = clean;
  e.push_back(ep(kR, "swa_bridge_1", topics::px4Out(topics::px4Namespace(2), "vehicle_attitude")));
  e.push_back(ep(kW, "swa_bridge_1", topics::imu(2)));
  e.push_back(ep(kR, "swa_agent_0", topics::px4Out(topics::px4Namespace(0), "vehicle_attitude")));
  e.erase(std::remove_if(e.begin(), e.end(),
                         [](const Endpoint& x) {
                           return x.participant == "swa_bridge_2" &&
                                  x.topic == topics::px4In(topics::px4Namespace(2), "trajectory_setpoint");
                         }),
          e.end());
  e.push_back(Endpoint{kR, "swa_bridge_0", "guid-twin", topics::cmdVel(0), "T"});
  const std::vector<std::string> v = auditBridges(e, 3, px4Topics(topics::px4Namespace));
  // THEN each is named
  EXPECT_TRUE(mentions(v, {"swa_bridge_1", "reads rt/px4_2/fmu/out/vehicle_attitude"})) << joined(v);
  EXPECT_TRUE(mentions(v, {"swa_bridge_1", "writes swa/uav2/imu"})) << joined(v);
  EXPECT_TRUE(mentions(v, {"swa_agent_0", "touches PX4's rt/px4_0/fmu/out/vehicle_attitude"})) << joined(v);
  EXPECT_TRUE(mentions(v, {"swa_bridge_2 has no writer on rt/px4_2/fmu/in/trajectory_setpoint"})) << joined(v);
  EXPECT_TRUE(mentions(v, {"2 participants are named swa_bridge_0"})) << joined(v);
  EXPECT_EQ(v.size(), 5u) << joined(v);
}

// What a run through ArduPilot creates beside the agents: the stand-in (in swa_sim) and bridge I on ap/v<I+1>.
std::vector<Endpoint> ardupilotSwarm(int n) {
  std::vector<Endpoint> e = cleanSwarm(n);
  for (int i = 0; i < n; ++i) {
    const std::string bridge = "swa_bridge_" + std::to_string(i);
    const std::string ns = topics::apNamespace(i);
    for (const char* t : {"imu/experimental/data", "status"}) {
      e.push_back(ep(kW, "swa_sim", topics::apTopic(ns, t)));
      e.push_back(ep(kR, bridge, topics::apTopic(ns, t)));
    }
    e.push_back(ep(kW, bridge, topics::apTopic(ns, "cmd_vel")));
    e.push_back(ep(kR, "swa_sim", topics::apTopic(ns, "cmd_vel")));
    for (const char* service : {"arm_motors", "mode_switch"}) {
      e.push_back(ep(kW, bridge, topics::apRequest(ns, service)));
      e.push_back(ep(kR, bridge, topics::apReply(ns, service)));
    }
    e.push_back(ep(kW, bridge, topics::imu(i)));
    e.push_back(ep(kR, bridge, topics::cmdVel(i)));
    e.push_back(ep(kW, bridge, topics::bridgeState(i)));
  }
  return e;
}

TEST(IsolationAudit, ArdupilotBridgesTouchOnlyTheirOwnVehicleAndUav) {
  // GIVEN what a run through ArduPilot creates THEN the bridges pass
  const std::vector<Endpoint> clean = ardupilotSwarm(3);
  const std::vector<std::string> none = auditBridges(clean, 3, ardupilotTopics(topics::apNamespace));
  EXPECT_TRUE(none.empty()) << joined(none);
  // WHEN bridge 1 commands vehicle 2, reads its own cmd_vel back, bridge 0 asks vehicle 1 to arm, and agent 2 reads
  // its vehicle's status itself
  std::vector<Endpoint> e = clean;
  e.push_back(ep(kW, "swa_bridge_1", topics::apTopic(topics::apNamespace(2), "cmd_vel")));
  e.push_back(ep(kR, "swa_bridge_1", topics::apTopic(topics::apNamespace(1), "cmd_vel")));
  e.push_back(ep(kW, "swa_bridge_0", topics::apRequest(topics::apNamespace(1), "arm_motors")));
  e.push_back(ep(kR, "swa_agent_2", topics::apTopic(topics::apNamespace(2), "status")));
  const std::vector<std::string> v = auditBridges(e, 3, ardupilotTopics(topics::apNamespace));
  // THEN each is named
  EXPECT_TRUE(mentions(v, {"swa_bridge_1", "writes rt/ap/v3/cmd_vel"})) << joined(v);
  EXPECT_TRUE(mentions(v, {"swa_bridge_1", "reads rt/ap/v2/cmd_vel"})) << joined(v);
  EXPECT_TRUE(mentions(v, {"swa_bridge_0", "writes rq/ap/v2/arm_motorsRequest"})) << joined(v);
  EXPECT_TRUE(mentions(v, {"swa_agent_2", "touches ArduPilot's rt/ap/v3/status"})) << joined(v);
  EXPECT_EQ(v.size(), 4u) << joined(v);
}

TEST(IsolationAudit, TableListsEveryEndpointSorted) {
  const std::string t = endpointTable({ep(kW, "swa_sim", topics::kTruth), ep(kR, "swa_agent_0", topics::imu(0))});
  EXPECT_LT(t.find("swa_agent_0 [guid-swa_agent_0]  reads   swa/uav0/imu  (T)"), t.find("swa_sim")) << t;
  EXPECT_NE(t.find("swa_sim [guid-swa_sim]  writes  swa/truth  (T)"), std::string::npos) << t;
}

}  // namespace
}  // namespace swa::testing

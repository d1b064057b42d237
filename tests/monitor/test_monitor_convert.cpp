// Messages -> the monitor's inputs: an AgentState published by the agent node gives exactly the EstimateRecord
// monitor::estimateFromDiagnostics gives for the agent's own diagnostics (the rule swa_batch scores by); truth and
// events keep every field; malformed values (unknown enums, NaN, huge ids, too many neighbours) never make an
// estimate valid.

#include <gtest/gtest.h>

#include <cstdint>
#include <limits>

#include "msg_convert.h"
#include "swa/agent/diagnostics.h"
#include "swa/wire/agent_state.h"

namespace swa::monitor_node {
namespace {

constexpr double kNotANumber = std::numeric_limits<double>::quiet_NaN();

agent::Diagnostics tracking(agent::Mode mode = agent::Mode::kSwa) {
  agent::Diagnostics d;
  d.stamp_ns = 12'300'000'000;
  d.mode = mode;
  d.stage = agent::Stage::kTracking;
  d.position_m = agent::Vec2(0.25, -0.5);
  d.velocity_mps = agent::Vec2(0.01, 0.02);
  d.position_cov_m2 << 0.04, 0.001, 0.001, 0.05;
  d.velocity_cov_m2ps2 << 0.002, -0.0001, -0.0001, 0.003;
  d.frame_valid = true;
  d.frame_centre_m = agent::Vec2(-0.25, 0.5);
  d.neighbour_count = 3;
  d.neighbour_ids[0] = 4;
  d.neighbour_ids[1] = 1;
  d.neighbour_ids[2] = 7;
  return d;
}

agent::FormationConfig formation(double radius, agent::CircleFit fit) {
  agent::FormationConfig f;
  f.radius_m = radius;
  f.circle_fit = fit;
  return f;
}

void expectSameRecord(const monitor::EstimateRecord& a, const monitor::EstimateRecord& b) {
  EXPECT_EQ(a.valid, b.valid);
  EXPECT_EQ(a.position_m, b.position_m);
  EXPECT_EQ(a.position_cov_m2, b.position_cov_m2);
  EXPECT_EQ(a.velocity_mps, b.velocity_mps);
  EXPECT_EQ(a.velocity_cov_m2ps2, b.velocity_cov_m2ps2);
  EXPECT_EQ(a.neighbour_count, b.neighbour_count);
  EXPECT_EQ(a.neighbour_ids, b.neighbour_ids);
  EXPECT_EQ(a.formation.radius_m, b.formation.radius_m);
  EXPECT_EQ(a.formation.circle_fit, b.formation.circle_fit);
}

TEST(MonitorConvert, StateGivesTheRecordOfTheAgentsOwnDiagnostics) {
  // GIVEN a formation of radius 12.5 m with the algebraic fit
  const agent::FormationConfig f = formation(12.5, agent::CircleFit::kAlgebraic);
  for (const agent::Mode mode : {agent::Mode::kSwa, agent::Mode::kAnchored, agent::Mode::kStandalone}) {
    // AND a tracking agent's diagnostics in each mode
    const agent::Diagnostics d = tracking(mode);
    // WHEN they are published as UAV 3's AgentState and converted back
    const StateSample s = fromStateMsg(wire::toMsg(d, 3, 17), f);
    // THEN the sample carries the UAV, stamp and mode, all finite
    EXPECT_EQ(s.uav, 3);
    EXPECT_EQ(s.stamp_ns, d.stamp_ns);
    ASSERT_TRUE(s.mode.has_value());
    EXPECT_EQ(*s.mode, mode);
    EXPECT_TRUE(s.finite);
    // AND its estimate is exactly the record the agent's own diagnostics give (valid unless standalone), with the
    // formation's radius and fit
    expectSameRecord(s.estimate, monitor::estimateFromDiagnostics(d, f));
    EXPECT_EQ(s.estimate.valid, mode != agent::Mode::kStandalone);
    EXPECT_EQ(s.estimate.formation.radius_m, 12.5);  // from the scenario's formation: the message has no radius
    EXPECT_EQ(s.estimate.formation.circle_fit, agent::CircleFit::kAlgebraic);
  }
}

TEST(MonitorConvert, OnlyATrackedFloatingFrameIsValid) {
  // GIVEN a formation and a conversion that says whether the estimate is valid
  const agent::FormationConfig f = formation(10.0, agent::CircleFit::kFixedRadius);
  const auto valid = [&f](const agent::Diagnostics& d) { return fromStateMsg(wire::toMsg(d, 0, 1), f).estimate.valid; };
  // THEN a tracking agent's estimate is valid
  EXPECT_TRUE(valid(tracking()));
  // WHEN the agent is initialising or lost THEN it is not
  agent::Diagnostics d = tracking();
  d.stage = agent::Stage::kInitializing;
  EXPECT_FALSE(valid(d));
  d.stage = agent::Stage::kLost;
  EXPECT_FALSE(valid(d));
  // WHEN the frame is not valid THEN it is not
  d = tracking();
  d.frame_valid = false;
  EXPECT_FALSE(valid(d));
  // WHEN the agent has no neighbour THEN it is not
  d = tracking();
  d.neighbour_count = 0;
  EXPECT_FALSE(valid(d));
}

TEST(MonitorConvert, UnknownEnumValuesMakeTheEstimateInvalid) {
  // GIVEN the default formation
  const agent::FormationConfig f;
  // WHEN a tracking agent's state has an unknown mode value THEN the sample has no mode and the estimate is invalid
  msg::AgentState m = wire::toMsg(tracking(), 0, 1);
  m.mode(static_cast<msg::AgentMode>(42));
  StateSample s = fromStateMsg(m, f);
  EXPECT_FALSE(s.mode.has_value());
  EXPECT_FALSE(s.estimate.valid);

  // WHEN the state has an unknown stage value THEN the mode is kept and the estimate is invalid
  m = wire::toMsg(tracking(), 0, 1);
  m.stage(static_cast<msg::AgentStage>(42));
  s = fromStateMsg(m, f);
  EXPECT_TRUE(s.mode.has_value());
  EXPECT_FALSE(s.estimate.valid);
}

TEST(MonitorConvert, NonFiniteNumbersMakeTheEstimateInvalid) {
  // GIVEN the default formation
  const agent::FormationConfig f;
  // WHEN one number of a tracking agent's state (position, velocity, a covariance) is NaN or infinite
  for (int field = 0; field < 4; ++field) {
    msg::AgentState m = wire::toMsg(tracking(), 0, 1);
    if (field == 0) m.est_x_m(kNotANumber);
    if (field == 1) m.est_vy_mps(std::numeric_limits<double>::infinity());
    if (field == 2) m.pos_cov_xy_m2(kNotANumber);
    if (field == 3) m.vel_cov_yy_m2ps2(kNotANumber);
    // THEN the sample is marked non-finite and its estimate invalid
    const StateSample s = fromStateMsg(m, f);
    EXPECT_FALSE(s.finite) << field;
    EXPECT_FALSE(s.estimate.valid) << field;
  }
}

TEST(MonitorConvert, TooManyNeighboursNeverScoreATruncatedFrame) {
  // GIVEN a tracking agent's state message that lists 40 neighbours
  msg::AgentState m = wire::toMsg(tracking(), 0, 1);
  m.neighbour_ids().assign(40, 1);
  // WHEN it is converted THEN all 40 are counted
  const StateSample s = fromStateMsg(m, agent::FormationConfig{});
  EXPECT_EQ(s.estimate.neighbour_count, 40);  // more than kMaxNeighbours: the NEES skips it as invalid
  // WHEN its estimate is scored in a step THEN the NEES skips it as invalid
  monitor::StepInput step;
  for (int i = 0; i < 2; ++i) step.uavs.push_back({i, agent::Vec2(10.0 * i, 0.0), agent::Vec2::Zero(), true});
  step.estimates = {s.estimate, monitor::EstimateRecord{}};
  const monitor::NeesStep nees = monitor::computeNees(step, monitor::FrameVelocity::kNeighbourMean);
  EXPECT_EQ(nees.evaluated, 0);
  EXPECT_EQ(nees.skipped_invalid, 1);
}

TEST(MonitorConvert, HugeUavIdsNeverAliasAUav) {
  // GIVEN a state message of UAV id 2^32 - 1 WHEN it is converted THEN its UAV is -1 (none)
  msg::AgentState m = wire::toMsg(tracking(), 0, 1);
  m.uav_id(std::numeric_limits<std::uint32_t>::max());
  EXPECT_EQ(fromStateMsg(m, agent::FormationConfig{}).uav, -1);
  // AND a UAV of that id in a truth message converts to -1 too
  msg::SwarmTruth t;
  msg::UavTruth u;
  u.id(std::numeric_limits<std::uint32_t>::max());
  t.uavs().push_back(u);
  EXPECT_EQ(fromTruthMsg(t).uavs.at(0).id, -1);
}

TEST(MonitorConvert, TruthKeepsEveryUavInTheAirAndTheAgentFlagApart) {
  // GIVEN a truth message of 3 UAVs at 2 s, in which agent 1 is dead
  msg::SwarmTruth m;
  m.header().stamp_ns(2'000'000'000);
  for (std::uint32_t i = 0; i < 3; ++i) {
    msg::UavTruth u;
    u.id(i);
    u.x_m(1.0 + i);
    u.y_m(-2.0 * i);
    u.vx_mps(0.5);
    u.vy_mps(-0.25 * i);
    u.alive(i != 1);  // the simulator's flag: agent 1 is dead, its UAV hovers on the failsafe
    m.uavs().push_back(u);
  }
  // WHEN it is converted
  const TruthSample t = fromTruthMsg(m);
  // THEN every UAV is kept with its id, position and velocity, alive (in the air) and present in the metrics
  EXPECT_EQ(t.stamp_ns, 2'000'000'000);
  ASSERT_EQ(t.uavs.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(t.uavs[i].id, static_cast<int>(i));
    EXPECT_TRUE(t.uavs[i].alive);  // in the air, so in every metric
    EXPECT_TRUE(monitor::isPresent(t.uavs[i]));
    EXPECT_EQ(t.uavs[i].position_m, agent::Vec2(1.0 + static_cast<double>(i), -2.0 * static_cast<double>(i)));
    EXPECT_EQ(t.uavs[i].velocity_mps, agent::Vec2(0.5, -0.25 * static_cast<double>(i)));
  }
  // AND the agent flags are kept apart
  EXPECT_EQ(t.agent_alive, (std::vector<bool>{true, false, true}));
}

TEST(MonitorConvert, EveryEventKindHasAName) {
  // GIVEN every event kind the simulator sends, with its name
  const std::pair<msg::EventKind, const char*> kinds[] = {{msg::EVENT_GNSS_LOST, "gnss_lost"},
                                                          {msg::EVENT_GNSS_RESTORED, "gnss_restored"},
                                                          {msg::EVENT_AGENT_DEAD, "agent_dead"},
                                                          {msg::EVENT_AGENT_REJOINED, "agent_rejoined"},
                                                          {msg::EVENT_COLLISION, "collision"},
                                                          {msg::EVENT_FAILSAFE, "failsafe"},
                                                          {msg::EVENT_SCENARIO_END, "scenario_end"},
                                                          {msg::EVENT_CONTROL_LOST, "control_lost"},
                                                          {msg::EVENT_CONTROL_REGAINED, "control_regained"}};
  for (const auto& [kind, name] : kinds) {
    // WHEN an event of that kind with every field set is converted
    msg::ScenarioEvent m;
    m.header().stamp_ns(1'500'000'000);
    m.kind(kind);
    m.uav_id(2);
    m.other_uav_id(3);
    m.value(1.25);
    m.text("detail, with a comma");
    const std::optional<EventRecord> e = fromEventMsg(m);
    // THEN it carries the kind's name and every field, its stamp in seconds
    ASSERT_TRUE(e.has_value()) << name;
    EXPECT_EQ(e->kind, name);
    EXPECT_DOUBLE_EQ(e->t_s, 1.5);
    EXPECT_EQ(e->uav, 2);
    EXPECT_EQ(e->other_uav, 3);
    EXPECT_DOUBLE_EQ(e->value, 1.25);
    EXPECT_EQ(e->text, "detail, with a comma");
  }
  // AND an unknown kind gives no event
  msg::ScenarioEvent unknown;
  unknown.kind(static_cast<msg::EventKind>(99));
  EXPECT_FALSE(fromEventMsg(unknown).has_value());
}

}  // namespace
}  // namespace swa::monitor_node

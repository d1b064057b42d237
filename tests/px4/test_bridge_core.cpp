// The autopilot bridge's rules (swa/autopilot/bridge_core.h) on a synthetic vehicle: PX4 attitude samples every 10 ms
// of vehicle time, agent commands, and a local clock the test advances (no sleeps).

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "swa/autopilot/bridge_core.h"
#include "swa/px4/vehicle.h"
#include "swa/wire/px4.h"

namespace swa::autopilot {
namespace {

using namespace swa::px4;  // PX4's attitudes, states and the vehicle constants the rules are tested with

constexpr std::uint64_t kStepUs = 10'000;  // 100 Hz attitude
constexpr std::uint64_t kBootUs = 5'000'000;

class BridgeCoreTest : public ::testing::Test {
 protected:
  explicit BridgeCoreTest(BridgeConfig config = {}) : bridge_(config) {}

  // One attitude sample `steps` after boot, arriving `steps` * 10 ms after the local clock's zero; then a tick.
  std::optional<agent::ImuSample> attitude(int steps, Quaternion q = {}) {
    now_s_ = steps * 0.01;
    auto imu = bridge_.onAttitude(stamp(steps), q, now_s_);
    last_tick_ = bridge_.tick(now_s_);
    return imu;
  }
  static std::uint64_t stamp(int steps) { return kBootUs + static_cast<std::uint64_t>(steps) * kStepUs; }

  Outbox command(int answered_step, agent::Vec2 v = {1.0, 0.5}, double yaw_rate_radps = 0.0) {
    agent::VelocityCommand c;
    c.answered_stamp_ns = static_cast<agent::StampNs>(stamp(answered_step)) * 1000;
    c.stamp_ns = c.answered_stamp_ns;
    c.velocity_mps = v;
    c.yaw_rate_radps = yaw_rate_radps;
    c.fresh = true;
    return bridge_.onCommand(c, now_s_);
  }

  // Attitude and an answer for every step in [from, to).
  void flyAnswered(int from, int to) {
    for (int k = from; k < to; ++k) {
      attitude(k);
      command(k);
    }
  }

  BridgeCore bridge_;
  double now_s_ = 0.0;
  Outbox last_tick_;
};

TEST_F(BridgeCoreTest, AttitudeIsForwardedOnTheVehiclesClockAndCorruptSamplesAreDropped) {
  // WHEN PX4 sends a level attitude heading east
  const auto imu = attitude(3, {std::cos(M_PI / 4), 0.0, 0.0, std::sin(M_PI / 4)});
  // THEN the agent gets it stamped with the same instant in ns, heading 0 (east)
  ASSERT_TRUE(imu);
  EXPECT_EQ(imu->stamp_ns, static_cast<agent::StampNs>(stamp(3)) * 1000);
  EXPECT_NEAR(imu->heading_rad, 0.0, 1e-12);
  // WHEN a sample is not a unit quaternion, or not newer THEN it is dropped and counted
  EXPECT_FALSE(attitude(4, {0.0, 0.0, 0.0, 0.0}));
  EXPECT_FALSE(attitude(3));
  EXPECT_EQ(bridge_.counters().attitude_rejected, 1u);
  EXPECT_EQ(bridge_.counters().attitude_out_of_order, 1u);
  // AND no offboard stream starts without a command of the agent
  EXPECT_EQ(bridge_.link(), Link::kNoAgent);
  EXPECT_FALSE(last_tick_.heartbeat_us);
}

TEST_F(BridgeCoreTest, ACommandIsSentAtOnceStampedWithTheSampleItAnswers) {
  // GIVEN samples forwarded
  attitude(0);
  attitude(1);
  // WHEN the agent answers sample 1 with 1 m/s east, 0.5 m/s north
  const Outbox out = command(1);
  // THEN a velocity setpoint in NED and a heartbeat go out, both stamped with sample 1's PX4 timestamp
  ASSERT_TRUE(out.setpoint);
  EXPECT_EQ(out.setpoint->timestamp_us, stamp(1));
  EXPECT_EQ(out.setpoint->velocity.north, 0.5);
  EXPECT_EQ(out.setpoint->velocity.east, 1.0);
  EXPECT_EQ(out.setpoint->velocity.down, 0.0);
  EXPECT_EQ(out.heartbeat_us, std::optional<std::uint64_t>(stamp(1)));
  EXPECT_EQ(bridge_.tick(now_s_).heartbeat_us, std::nullopt);  // no second heartbeat within the period
  EXPECT_EQ(bridge_.link(), Link::kFresh);
}

TEST_F(BridgeCoreTest, TheYawRateGoesOutAsYawspeedInNedAndTheStopHoldsTheHeading) {
  // GIVEN samples forwarded
  attitude(0);
  attitude(1);
  // WHEN the agent turns left (counter-clockwise from above) at 0.3 rad/s
  const Outbox out = command(1, {1.0, 0.5}, 0.3);
  // THEN PX4 is sent yawspeed -0.3 (about NED down, clockwise positive), and yaw NaN so that it follows the rate
  ASSERT_TRUE(out.setpoint);
  EXPECT_EQ(out.setpoint->yawspeed_radps, -0.3);
  const px4_msgs::msg::TrajectorySetpoint sent = wire::trajectorySetpoint(*out.setpoint);
  EXPECT_EQ(sent.yawspeed(), -0.3f);
  EXPECT_TRUE(std::isnan(sent.yaw()));
  EXPECT_EQ(wire::yawspeedOf(sent), static_cast<double>(-0.3f));

  // WHEN the agent then falls silent until its command is stale
  std::optional<Setpoint> stop;
  for (int k = 2; k <= 60 && !stop; ++k) {
    attitude(k);
    stop = last_tick_.setpoint;
  }
  // THEN the bridge's own stop command holds the heading: yawspeed exactly 0, not the last rate and not NaN
  ASSERT_TRUE(stop);
  EXPECT_EQ(bridge_.link(), Link::kStale);
  EXPECT_EQ(stop->yawspeed_radps, 0.0);
  EXPECT_EQ(wire::trajectorySetpoint(*stop).yawspeed(), 0.0f);

  // WHEN a command's yaw rate is NaN or infinite THEN it never becomes a setpoint; a too fast turn is clamped
  attitude(61);
  EXPECT_FALSE(command(61, {0.0, 0.0}, std::nan("")).setpoint);
  EXPECT_FALSE(command(61, {0.0, 0.0}, -std::numeric_limits<double>::infinity()).setpoint);
  EXPECT_EQ(bridge_.counters().commands_nonfinite, 2u);
  const Outbox fast = command(61, {0.0, 0.0}, -1e300);
  ASSERT_TRUE(fast.setpoint);
  EXPECT_EQ(fast.setpoint->yawspeed_radps, BridgeConfig{}.max_yaw_rate_radps);
  EXPECT_EQ(bridge_.counters().commands_clamped, 1u);
}

TEST_F(BridgeCoreTest, CommandsFromBeforeTheBridgeOrForUnknownOrOlderSamplesAreIgnored) {
  // GIVEN a bridge whose first forwarded sample is step 10 (restarted: its writer's last command answers step 9)
  attitude(10);
  attitude(11);
  // WHEN the agent's old command (step 9), one for a sample never forwarded (12), and two for step 11 arrive
  EXPECT_FALSE(command(9).setpoint);
  EXPECT_FALSE(command(12).setpoint);
  EXPECT_TRUE(command(11).setpoint);
  EXPECT_FALSE(command(11).setpoint);
  EXPECT_FALSE(command(10).setpoint);
  // THEN each is counted by its reason
  EXPECT_EQ(bridge_.counters().commands_replayed, 1u);
  EXPECT_EQ(bridge_.counters().commands_unknown_sample, 1u);
  EXPECT_EQ(bridge_.counters().commands_not_newer, 2u);
  EXPECT_EQ(bridge_.counters().commands_applied, 1u);
  // AND a non-finite command never becomes a setpoint, a too fast one is clamped
  attitude(12);
  EXPECT_FALSE(command(12, {std::nan(""), 0.0}).setpoint);
  const Outbox fast = command(12, {30.0, 40.0});
  ASSERT_TRUE(fast.setpoint);
  EXPECT_NEAR(std::hypot(fast.setpoint->velocity.north, fast.setpoint->velocity.east), 5.0, 1e-12);
  EXPECT_EQ(bridge_.counters().commands_clamped, 1u);
}

TEST_F(BridgeCoreTest, AStaleCommandBecomesZeroVelocityThenALostAgentStopsTheHeartbeat) {
  // GIVEN the agent answered every sample up to step 20
  flyAnswered(0, 21);
  ASSERT_EQ(bridge_.link(), Link::kFresh);
  // WHEN it falls silent while PX4 keeps sending attitude for 1.2 s of vehicle time
  int zero_setpoints = 0, heartbeats = 0, first_stale = -1, lost_at = -1;
  for (int k = 21; k <= 140; ++k) {
    attitude(k);
    if (last_tick_.setpoint) {
      EXPECT_EQ(last_tick_.setpoint->velocity.north, 0.0);
      EXPECT_EQ(last_tick_.setpoint->velocity.east, 0.0);
      EXPECT_EQ(last_tick_.setpoint->timestamp_us, stamp(20));  // answers no new sample
      ++zero_setpoints;
      if (first_stale < 0) first_stale = k;
    }
    if (last_tick_.heartbeat_us) ++heartbeats;
    if (bridge_.link() == Link::kAgentLost && lost_at < 0) lost_at = k;
  }
  // THEN 0.3 s after the last answered sample the stream turns to zero velocity, once ...
  EXPECT_EQ(first_stale, 20 + 31);
  EXPECT_EQ(zero_setpoints, 1);
  // ... the heartbeat goes on at 20 Hz while the agent may come back, and stops once it is lost (1 s)
  EXPECT_EQ(lost_at, 20 + 101);
  EXPECT_GE(heartbeats, 10);  // 0.7 s of stale streaming at 20 Hz: 14
  for (int k = 141; k < 200; ++k) {
    attitude(k);
    EXPECT_FALSE(last_tick_.heartbeat_us || last_tick_.setpoint) << k;
  }
  // AND each change was reported
  const std::vector<std::string> events = bridge_.takeEvents();
  std::string all;
  for (const std::string& e : events) all += e + "\n";
  EXPECT_NE(all.find("command stale"), std::string::npos) << all;
  EXPECT_NE(all.find("agent lost"), std::string::npos) << all;

  // WHEN the agent (restarted) answers again THEN the stream resumes at once
  attitude(200);
  EXPECT_TRUE(command(200).setpoint);
  bridge_.tick(now_s_);
  EXPECT_EQ(bridge_.link(), Link::kFresh);
}

TEST_F(BridgeCoreTest, TheHeartbeatKeepsItsRateWhenCommandsAreSparse) {
  // GIVEN PX4 sends attitude at only 5 Hz and the agent answers each sample
  int heartbeats = 0;
  for (int k = 0; k <= 100; ++k) {
    now_s_ = k * 0.01;
    if (k % 20 == 0) {
      bridge_.onAttitude(stamp(k), {}, now_s_);
      if (command(k).heartbeat_us) ++heartbeats;
    }
    if (bridge_.tick(now_s_).heartbeat_us) ++heartbeats;
  }
  // THEN over one second the offboard stream still has at least 10 heartbeats (20 Hz)
  EXPECT_GE(heartbeats, 20);
}

TEST_F(BridgeCoreTest, PX4FallingSilentStopsTheStream) {
  // GIVEN a fresh stream
  flyAnswered(0, 5);
  // WHEN no attitude comes for 0.6 s of local time
  now_s_ += 0.6;
  const Outbox out = bridge_.tick(now_s_);
  // THEN the bridge stops streaming rather than hold the last command on a vehicle it cannot see
  EXPECT_EQ(bridge_.link(), Link::kAttitudeLost);
  EXPECT_FALSE(out.heartbeat_us || out.setpoint);
}

TEST_F(BridgeCoreTest, PX4sClockRestartStartsANewTimeline) {
  flyAnswered(100, 110);
  // WHEN PX4 restarts (its timestamps start again near zero)
  now_s_ += 0.01;
  const auto imu = bridge_.onAttitude(kStepUs, {}, now_s_);
  // THEN the sample is forwarded, and a command answering the old timeline is not applied
  ASSERT_TRUE(imu);
  EXPECT_EQ(bridge_.counters().clock_restarts, 1u);
  agent::VelocityCommand old;
  old.answered_stamp_ns = static_cast<agent::StampNs>(stamp(109)) * 1000;
  EXPECT_FALSE(bridge_.onCommand(old, now_s_).setpoint);
}

TEST_F(BridgeCoreTest, AClockSetAheadStartsANewTimelineAndKeepsTheAgent) {
  flyAnswered(100, 110);
  // WHEN the vehicle's stamps jump from time since boot to UTC 10 ms later (ArduPilot once its clock is set)
  constexpr std::uint64_t kUtcUs = 1'795'000'000'000'000;
  now_s_ += 0.01;
  ASSERT_TRUE(bridge_.onAttitude(kUtcUs, {}, now_s_));
  // THEN it is a new timeline, not a lifetime without commands: the stream is not stopped as "agent lost"
  EXPECT_EQ(bridge_.counters().clock_restarts, 1u);
  bridge_.tick(now_s_);
  EXPECT_NE(bridge_.link(), Link::kAgentLost);
  // AND the agent's answer to the new sample is applied, one to the old timeline is not
  agent::VelocityCommand c;
  c.answered_stamp_ns = static_cast<agent::StampNs>(stamp(109)) * 1000;
  c.velocity_mps = {1.0, 0.0};
  EXPECT_FALSE(bridge_.onCommand(c, now_s_).setpoint);
  c.answered_stamp_ns = static_cast<agent::StampNs>(kUtcUs) * 1000;
  EXPECT_TRUE(bridge_.onCommand(c, now_s_).setpoint);
}

TEST_F(BridgeCoreTest, AGapTheLocalClockAlsoSawIsNoClockJump) {
  flyAnswered(100, 110);
  // WHEN the vehicle is silent for 3 s and then goes on where its clock and ours agree
  attitude(410);
  // AND a simulator at 50 times real time jumps 50 s ahead in a pause of a second of ours
  now_s_ += 1.0;
  ASSERT_TRUE(bridge_.onAttitude(stamp(410) + 50'000'000u, {}, now_s_));
  // THEN the samples are one timeline
  EXPECT_EQ(bridge_.counters().clock_restarts, 0u);
}

TEST_F(BridgeCoreTest, WithoutEngageTheBridgeNeverArmsOrSwitchesModes) {
  // GIVEN a disarmed vehicle in hold and the agent streaming for 3 s
  bridge_.onStatus(false, kNavStateAutoLoiter);
  for (int k = 0; k < 300; ++k) {
    attitude(k);
    EXPECT_FALSE(last_tick_.request) << k;
    command(k);
  }
  EXPECT_EQ(bridge_.counters().requests_out, 0u);
}

class EngagingBridge : public BridgeCoreTest {
 protected:
  static BridgeConfig engaging() {
    BridgeConfig c;
    c.engage = true;
    return c;
  }
  EngagingBridge() : BridgeCoreTest(engaging()) {}
};

TEST_F(EngagingBridge, ArmsThenRequestsOffboardOnceTheStreamRuns) {
  // GIVEN --engage, a disarmed vehicle in hold, and the agent answering every sample
  bridge_.onStatus(false, kNavStateAutoLoiter);
  std::vector<std::pair<int, VehicleRequest>> requests;
  for (int k = 0; k < 400; ++k) {
    attitude(k);
    if (last_tick_.request) requests.emplace_back(k, *last_tick_.request);
    command(k);
    // The vehicle obeys the first arm request, and the first offboard request a second later.
    if (!requests.empty() && k == requests.front().first + 1) bridge_.onStatus(true, kNavStateAutoLoiter);
    if (requests.size() == 2 && k == requests.back().first + 1) bridge_.onStatus(true, kNavStateOffboard);
  }
  // THEN it asks to arm after 1 s of streaming (the stream starts at step 1, after the first answer), then for
  // offboard (at most once a second), then nothing more
  ASSERT_EQ(requests.size(), 2u);
  EXPECT_EQ(requests[0].second, VehicleRequest::kArm);
  EXPECT_EQ(requests[0].first, 101);
  EXPECT_EQ(requests[1].second, VehicleRequest::kControlMode);
  EXPECT_EQ(requests[1].first, 201);
}

TEST_F(EngagingBridge, NeverEngagesOnAStaleStream) {
  // GIVEN --engage and an agent that answered only at the start
  bridge_.onStatus(true, kNavStateAutoLoiter);
  flyAnswered(0, 2);
  // WHEN only the bridge's own zero-velocity stream runs THEN no mode switch is requested
  for (int k = 2; k < 150; ++k) {
    attitude(k);
    EXPECT_FALSE(last_tick_.request) << k;
  }
}

}  // namespace
}  // namespace swa::autopilot

// ArduPilot's conventions (swa/autopilot/ardupilot.h, swa/wire/ardupilot.h) and the simulator's ArduPilot stand-in
// (swa/sim/ardupilot_standin.h), on simulation time (10 ms steps).

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "swa/autopilot/ardupilot.h"
#include "swa/autopilot/bridge_core.h"
#include "swa/autopilot/navsat.h"
#include "swa/sim/ardupilot_standin.h"
#include "swa/wire/ardupilot.h"

namespace swa::ardupilot {
namespace {

TEST(Ardupilot, StampsAreWholeMicrosecondsOfTheMessagesTime) {
  EXPECT_EQ(timestampUsOf(12, 345'678'000u), std::optional<std::uint64_t>(12'345'678u));
  EXPECT_EQ(timestampUsOf(1, 999u), std::optional<std::uint64_t>(1'000'000u));  // below a microsecond: dropped
  EXPECT_FALSE(timestampUsOf(-1, 0u));
  EXPECT_FALSE(timestampUsOf(0, 1'000'000'000u));
  const std::optional<RosTime> t = rosTimeOf(12'345'678u);
  ASSERT_TRUE(t);
  EXPECT_EQ(t->sec, 12);
  EXPECT_EQ(t->nanosec, 345'678'000u);
  EXPECT_FALSE(rosTimeOf(std::uint64_t{1} << 60));
}

TEST(Ardupilot, TheImuOrientationIsReadInEitherFieldOrder) {
  // GIVEN an attitude heading 30 deg east of north, 5 deg nose up (FRD -> NED, as ArduPilot's AHRS has it)
  const px4::Quaternion q = px4::quaternionOf(px4::Euler{0.0, 5.0 * M_PI / 180.0, 30.0 * M_PI / 180.0});
  // WHEN the stand-in writes it and the bridge reads it the ROS way THEN it is the same attitude
  const sensor_msgs::msg::Imu m = wire::imuMessage(7'000'000u, q);
  const px4::Quaternion back = wire::attitudeOf(m, QuaternionLayout::kRos);
  EXPECT_NEAR(back.w, q.w, 1e-15);
  EXPECT_NEAR(back.z, q.z, 1e-15);
  EXPECT_EQ(m.header().frame_id(), "base_link_ned");
  EXPECT_EQ(wire::timestampUsOf(m.header().stamp()), std::optional<std::uint64_t>(7'000'000u));
  // AND an early AP_DDS message, with w, x, y, z in the fields x, y, z, w, reads the same with the wxyz layout
  sensor_msgs::msg::Imu early;
  early.orientation().x(q.w);
  early.orientation().y(q.x);
  early.orientation().z(q.y);
  early.orientation().w(q.z);
  const px4::Quaternion fixed = wire::attitudeOf(early, QuaternionLayout::kWxyzInXyzw);
  EXPECT_NEAR(fixed.w, q.w, 1e-15);
  EXPECT_NEAR(fixed.x, q.x, 1e-15);
  EXPECT_NEAR(fixed.y, q.y, 1e-15);
  EXPECT_NEAR(fixed.z, q.z, 1e-15);
  // AND read the ROS way it is no level flight: what the bridge's warning looks for
  const px4::Euler wrong = px4::eulerOf(wire::attitudeOf(early, QuaternionLayout::kRos));
  EXPECT_GT(std::max(std::abs(wrong.roll), std::abs(wrong.pitch)), 1.2);
}

autopilot::BridgeCore ardupilotCore() {
  autopilot::BridgeConfig config;
  config.autopilot = autopilot::ardupilotAutopilot();
  return autopilot::BridgeCore(config);
}

// The agent's answer to the sample stamped `timestamp_us`, at local time 0.
autopilot::Outbox answer(autopilot::BridgeCore& core, std::uint64_t timestamp_us, const agent::Vec2& v,
                         double yaw_rate_radps) {
  agent::VelocityCommand c;
  c.answered_stamp_ns = static_cast<agent::StampNs>(timestamp_us) * 1000;
  c.stamp_ns = c.answered_stamp_ns;
  c.velocity_mps = v;
  c.yaw_rate_radps = yaw_rate_radps;
  c.fresh = true;
  return core.onCommand(c, 0.0);
}

TEST(Ardupilot, TheCoresSetpointIsAnEnuCmdVelInTheMapFrame) {
  // GIVEN the bridge core configured for ArduPilot, one attitude sample and the agent's answer: 1 m/s east, 0.5 m/s
  // north, turning left (counter-clockwise) at 0.3 rad/s
  autopilot::BridgeCore core = ardupilotCore();
  ASSERT_TRUE(core.onAttitude(5'000'000u, px4::Quaternion{}, 0.0));
  const autopilot::Outbox out = answer(core, 5'000'000u, agent::Vec2(1.0, 0.5), 0.3);
  ASSERT_TRUE(out.setpoint);
  // WHEN it goes out as cmd_vel THEN ENU, the same yaw rate (ROS's sense is SWA's), stamped with the sample's time
  const geometry_msgs::msg::TwistStamped m = wire::cmdVel(*out.setpoint);
  EXPECT_EQ(m.header().frame_id(), "map");
  EXPECT_EQ(m.header().stamp().sec(), 5);
  EXPECT_EQ(m.header().stamp().nanosec(), 0u);
  EXPECT_DOUBLE_EQ(m.twist().linear().x(), 1.0);
  EXPECT_DOUBLE_EQ(m.twist().linear().y(), 0.5);
  EXPECT_DOUBLE_EQ(m.twist().linear().z(), 0.0);
  EXPECT_DOUBLE_EQ(m.twist().angular().z(), 0.3);
  // AND the stand-in reads back what was sent
  const wire::CmdVel back = wire::cmdVelOf(m);
  EXPECT_TRUE(back.map_frame);
  EXPECT_EQ(back.timestamp_us, std::optional<std::uint64_t>(5'000'000u));
  EXPECT_EQ(stableVelocityOf(back.twist), agent::Vec2(1.0, 0.5));
  // AND no heartbeat goes with it, nor later: ArduPilot has none
  EXPECT_FALSE(out.heartbeat_us);
  EXPECT_FALSE(core.tick(0.2).heartbeat_us);
  EXPECT_EQ(core.counters().heartbeats_out, 0u);
  // AND the core names ArduPilot's GUIDED in its requests
  EXPECT_STREQ(core.autopilot().control_mode_name, "GUIDED");
  EXPECT_STREQ(copterModeName(kModeGuided), "GUIDED");
}

TEST(Ardupilot, AStaleCommandBecomesZeroVelocityRepeatedAtTheHeartbeatsPeriod) {
  // GIVEN the core for ArduPilot, attitude every 10 ms and one command answering the first sample
  autopilot::BridgeCore core = ardupilotCore();
  ASSERT_TRUE(core.onAttitude(1'000'000u, px4::Quaternion{}, 0.0));
  ASSERT_TRUE(answer(core, 1'000'000u, agent::Vec2(2.0, 0.0), 0.0).setpoint);
  // WHEN no further command comes while the vehicle's samples go on for 0.9 s
  int zeros = 0;
  for (int k = 1; k <= 90; ++k) {
    const double now = 0.01 * k;
    core.onAttitude(1'000'000u + 10'000u * static_cast<std::uint64_t>(k), px4::Quaternion{}, now);
    const autopilot::Outbox out = core.tick(now);
    EXPECT_FALSE(out.heartbeat_us);
    if (out.setpoint) {
      // THEN every setpoint is zero velocity, holding the heading, stamped like the last command's sample
      EXPECT_EQ(out.setpoint->timestamp_us, 1'000'000u);
      EXPECT_EQ(out.setpoint->velocity.north, 0.0);
      EXPECT_EQ(out.setpoint->velocity.east, 0.0);
      EXPECT_EQ(out.setpoint->yawspeed_radps, 0.0);
      ++zeros;
    }
  }
  // AND from the stale point (0.3 s) to 0.9 s it is repeated every 50 ms, not sent once: ArduPilot has no heartbeat
  // to keep a lost one from letting the vehicle fly the old command until GUID_TIMEOUT
  EXPECT_EQ(core.link(), autopilot::Link::kStale);
  EXPECT_GE(zeros, 11);
  EXPECT_LE(zeros, 13);
}

TEST(NavSat, FixesAreMetresEastAndNorthOfTheFirstOneAndBackWithinAMillimetre) {
  // GIVEN a local frame at a mid-latitude airfield
  const LocalTangent home{47.397742, 8.545594};
  // WHEN a position 1 km east and 2 km north is turned into latitude and longitude and back THEN it is the same
  double lat = 0.0, lon = 0.0;
  home.latLonOf(agent::Vec2(1000.0, 2000.0), lat, lon);
  EXPECT_GT(lat, home.origin_lat_deg);
  EXPECT_GT(lon, home.origin_lon_deg);
  EXPECT_NEAR((home.enuOf(lat, lon) - agent::Vec2(1000.0, 2000.0)).norm(), 0.0, 1e-3);
  // AND a degree of latitude there is WGS 84's 111.2 km, a degree of longitude 75.4 km
  EXPECT_NEAR(home.enuOf(home.origin_lat_deg + 1.0, home.origin_lon_deg).y(), 111'200.0, 100.0);
  EXPECT_NEAR(home.enuOf(home.origin_lat_deg, home.origin_lon_deg + 1.0).x(), 75'400.0, 100.0);
}

TEST(NavSat, AFixIsValidTheLossComesAsNoFixOrAsSilenceAndOnlyOnce) {
  NavSatForward f;
  const LocalTangent home{47.4, 8.5};
  double lat = 0.0, lon = 0.0;
  const auto fixAt = [&](std::uint64_t t_us, const agent::Vec2& enu, std::int8_t status = 0) {
    home.latLonOf(enu, lat, lon);
    NavSatReport r;
    r.timestamp_us = t_us;
    r.status = status;
    r.latitude_deg = lat;
    r.longitude_deg = lon;
    r.covariance_type = 2;
    r.variance_east_m2 = 0.64;
    r.variance_north_m2 = 0.36;
    return f.onNavSat(r);
  };
  // GIVEN a first fix and one 3 m east of it THEN both valid, positions relative to the first, std from the covariance
  const auto first = fixAt(1'000'000, agent::Vec2(10.0, 20.0));
  ASSERT_TRUE(first && first->valid);
  EXPECT_NEAR(first->position_m.norm(), 0.0, 1e-9);
  EXPECT_EQ(first->stamp_ns, 1'000'000'000);
  EXPECT_NEAR(first->std_m, std::sqrt(0.5), 1e-12);
  const auto second = fixAt(1'100'000, agent::Vec2(13.0, 20.0));
  ASSERT_TRUE(second && second->valid);
  EXPECT_NEAR(second->position_m.x(), 3.0, 1e-3);
  EXPECT_NEAR(second->position_m.y(), 0.0, 1e-3);
  // WHEN the vehicle's time goes on without a fix THEN nothing before 0.5 s; at 0.5 s, one loss, once
  EXPECT_FALSE(f.onVehicleTime(1'599'999));
  const auto lost = f.onVehicleTime(1'600'000);
  ASSERT_TRUE(lost);
  EXPECT_FALSE(lost->valid);
  EXPECT_EQ(lost->stamp_ns, 1'600'000'000);
  EXPECT_FALSE(f.onVehicleTime(1'610'000));
  EXPECT_FALSE(f.onVehicleTime(3'000'000));
  // WHEN fixes come again THEN valid at once; a report of no fix is a loss at once; an older report is dropped
  ASSERT_TRUE(fixAt(3'100'000, agent::Vec2(13.0, 21.0))->valid);
  const auto none = fixAt(3'200'000, agent::Vec2(13.0, 21.0), -1);
  ASSERT_TRUE(none);
  EXPECT_FALSE(none->valid);
  EXPECT_FALSE(fixAt(3'150'000, agent::Vec2(13.0, 21.0)));
  // AND a fix with a non-finite or impossible latitude is no fix
  NavSatReport bad;
  bad.timestamp_us = 3'300'000;
  bad.status = 0;
  bad.latitude_deg = std::nan("");
  EXPECT_FALSE(f.onNavSat(bad)->valid);
  bad.latitude_deg = 95.0;
  EXPECT_FALSE(f.onNavSat(bad)->valid);
}

}  // namespace
}  // namespace swa::ardupilot

namespace swa::sim {
namespace {

constexpr agent::StampNs kApStepNs = 10'000'000;
const ardupilot::EnuTwist kEast{1.0, 0.0, 0.0, 0.2};

TEST(ArdupilotStandin, FliesCmdVelOnlyInGuidedAndArmed) {
  ArdupilotStandin s(3.0);
  // GIVEN the vehicle as the scenario starts it: armed, LOITER
  EXPECT_TRUE(s.armed());
  EXPECT_EQ(s.mode(), ardupilot::kModeLoiter);
  // WHEN cmd_vel arrives in LOITER THEN it is dropped: the vehicle holds
  s.cmdVel(0, true, kEast);
  EXPECT_FALSE(s.step(kApStepNs).following);
  // WHEN GUIDED is requested THEN it switches, and the next cmd_vel is flown, yaw rate included
  const ArdupilotStandin::ModeReply r = s.modeSwitch(ardupilot::kModeGuided);
  EXPECT_TRUE(r.status);
  EXPECT_EQ(r.curr_mode, ardupilot::kModeGuided);
  EXPECT_FALSE(s.step(2 * kApStepNs).following);  // GUIDED starts from a stop
  s.cmdVel(2 * kApStepNs, true, kEast);
  const ArdupilotStandin::Decision d = s.step(3 * kApStepNs);
  EXPECT_TRUE(d.following);
  EXPECT_EQ(d.velocity_mps, agent::Vec2(1.0, 0.0));
  EXPECT_DOUBLE_EQ(d.yaw_rate_radps, 0.2);
  // WHEN it is disarmed THEN it no longer follows; a mode it does not simulate is refused and the mode kept
  EXPECT_TRUE(s.armMotors(false));
  EXPECT_FALSE(s.step(4 * kApStepNs).following);
  const ArdupilotStandin::ModeReply refused = s.modeSwitch(ardupilot::kModeRtl);
  EXPECT_FALSE(refused.status);
  EXPECT_EQ(refused.curr_mode, ardupilot::kModeGuided);
  const std::vector<StandinEvent> events = s.takeEvents();
  ASSERT_EQ(events.size(), 2u);
  EXPECT_EQ(events[0].text, "GUIDED on request");
  EXPECT_EQ(events[0].control, StandinEvent::Control::kRegained);
  EXPECT_EQ(events[1].text, "disarmed on request");
}

TEST(ArdupilotStandin, StopsAfterGuidTimeoutAndMovesAgainOnTheNextCmdVel) {
  ArdupilotStandin s(1.0);
  s.modeSwitch(ardupilot::kModeGuided);
  s.cmdVel(0, true, kEast);
  s.takeEvents();
  // GIVEN cmd_vel silent: it follows the last one up to GUID_TIMEOUT, then stops once, holding in GUIDED
  EXPECT_TRUE(s.step(100 * kApStepNs).following);
  EXPECT_FALSE(s.step(101 * kApStepNs).following);
  EXPECT_TRUE(s.timedOut());
  EXPECT_NEAR(s.silentForS(), 1.01, 1e-9);
  EXPECT_EQ(s.mode(), ardupilot::kModeGuided);
  std::vector<StandinEvent> events = s.takeEvents();
  ASSERT_EQ(events.size(), 1u);
  EXPECT_NE(events[0].text.find("no cmd_vel for 1.01 s (GUID_TIMEOUT)"), std::string::npos) << events[0].text;
  EXPECT_EQ(events[0].control, StandinEvent::Control::kLost);
  EXPECT_FALSE(s.step(150 * kApStepNs).following);
  EXPECT_TRUE(s.takeEvents().empty());
  // WHEN cmd_vel comes again THEN it follows at once
  s.cmdVel(200 * kApStepNs, true, kEast);
  EXPECT_TRUE(s.step(201 * kApStepNs).following);
  events = s.takeEvents();
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].text, "cmd_vel again: following it");
  EXPECT_EQ(events[0].control, StandinEvent::Control::kRegained);
}

TEST(ArdupilotStandin, OtherFramesAndNonFiniteCommandsAreNotFlown) {
  ArdupilotStandin s(3.0);
  s.modeSwitch(ardupilot::kModeGuided);
  s.takeEvents();
  // GIVEN cmd_vel in base_link (body frame), twice THEN dropped, said once
  s.cmdVel(0, false, kEast);
  s.cmdVel(kApStepNs, false, kEast);
  EXPECT_FALSE(s.step(2 * kApStepNs).following);
  EXPECT_EQ(s.takeEvents().size(), 1u);
  // GIVEN a NaN velocity THEN the vehicle holds instead of flying it
  s.cmdVel(3 * kApStepNs, true, ardupilot::EnuTwist{std::nan(""), 0.0, 0.0, 0.0});
  const ArdupilotStandin::Decision d = s.step(4 * kApStepNs);
  EXPECT_FALSE(d.following);
  EXPECT_EQ(d.velocity_mps, agent::Vec2::Zero());
}

}  // namespace
}  // namespace swa::sim

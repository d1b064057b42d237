// The agent's estimate as the autopilot's external odometry (issue #43): which states the bridge sends
// (swa/autopilot/odometry_feed.h) and how they look on each autopilot's wire (swa/wire/px4.h, swa/wire/ardupilot.h),
// read back as the stand-ins read them.

#include <gtest/gtest.h>

#include <cmath>

#include "swa/autopilot/odometry_feed.h"
#include "swa/px4/frames.h"
#include "swa/wire/ardupilot.h"
#include "swa/wire/px4.h"

namespace swa::autopilot {
namespace {

constexpr agent::StampNs kMs = 1'000'000;

agent::Diagnostics tracking(agent::StampNs stamp_ns, bool gnss) {
  agent::Diagnostics e;
  e.stamp_ns = stamp_ns;
  e.stage = agent::Stage::kTracking;
  e.gnss_valid = gnss;
  e.position_m = agent::Vec2(3.0, -4.0);  // east, north
  e.velocity_mps = agent::Vec2(0.5, 0.25);
  e.position_cov_m2 = agent::Mat2::Identity() * 0.25;
  e.velocity_cov_m2ps2 = agent::Mat2::Identity() * 0.04;
  return e;
}

TEST(OdometryFeed, FedWhileTheAgentHasNoGnssStoppedWhenItReturns) {
  OdometryFeed feed(OdometryFeedConfig{});
  // GIVEN an agent with GNSS THEN nothing goes out: the autopilot's own GNSS is used
  EXPECT_FALSE(feed.onState(tracking(1'000 * kMs, true), 1'000 * kMs));
  // WHEN it loses GNSS THEN its estimate goes out, as it is
  const std::optional<Odometry> o = feed.onState(tracking(1'100 * kMs, false), 1'120 * kMs);
  ASSERT_TRUE(o);
  EXPECT_TRUE(feed.feeding());
  EXPECT_EQ(o->stamp_ns, 1'100 * kMs);
  EXPECT_EQ(o->position_m, agent::Vec2(3.0, -4.0));
  EXPECT_EQ(o->velocity_mps, agent::Vec2(0.5, 0.25));
  EXPECT_EQ(o->position_var_m2, agent::Vec2(0.25, 0.25));
  // AND when GNSS returns it stops
  EXPECT_FALSE(feed.onState(tracking(1'200 * kMs, true), 1'200 * kMs));
  EXPECT_FALSE(feed.feeding());
  EXPECT_EQ(feed.counters().sent, 1u);
  EXPECT_EQ(feed.counters().skipped_gnss, 2u);
  // AND "always" feeds it with GNSS too, "off" never
  OdometryFeed always(OdometryFeedConfig{OdometryMode::kAlways});
  EXPECT_TRUE(always.onState(tracking(1'000 * kMs, true), 1'000 * kMs));
  OdometryFeed off(OdometryFeedConfig{OdometryMode::kOff});
  EXPECT_FALSE(off.onState(tracking(1'000 * kMs, false), 1'000 * kMs));
}

TEST(OdometryFeed, AStaleOrInvalidEstimateIsNeverSent) {
  OdometryFeed feed(OdometryFeedConfig{});
  // stale: 0.31 s behind the vehicle's newest attitude (and a state from the future no fresher)
  EXPECT_FALSE(feed.onState(tracking(1'000 * kMs, false), 1'310 * kMs));
  EXPECT_FALSE(feed.onState(tracking(2'000 * kMs, false), 1'000 * kMs));
  // not tracking, not finite, too uncertain
  agent::Diagnostics lost = tracking(3'000 * kMs, false);
  lost.stage = agent::Stage::kLost;
  EXPECT_FALSE(feed.onState(lost, 3'000 * kMs));
  agent::Diagnostics nan = tracking(3'100 * kMs, false);
  nan.velocity_mps.x() = std::nan("");
  EXPECT_FALSE(feed.onState(nan, 3'100 * kMs));
  agent::Diagnostics vague = tracking(3'200 * kMs, false);
  vague.position_cov_m2(1, 1) = 21.0 * 21.0;
  EXPECT_FALSE(feed.onState(vague, 3'200 * kMs));
  EXPECT_EQ(feed.counters().skipped_stale, 2u);
  EXPECT_EQ(feed.counters().skipped_invalid, 3u);
  EXPECT_EQ(feed.counters().sent, 0u);
}

TEST(OdometryFeed, ItStopsWhenTheAgentsStatesStopComing) {
  OdometryFeed feed(OdometryFeedConfig{});
  // GIVEN a feed in progress
  ASSERT_TRUE(feed.onState(tracking(1'000 * kMs, false), 1'000 * kMs));
  // WHEN no state follows THEN it still counts as feeding for stale_after_s of the vehicle's time ...
  EXPECT_FALSE(feed.expire(1'300 * kMs));
  EXPECT_TRUE(feed.feeding());
  // ... and has stopped after it, said once
  EXPECT_TRUE(feed.expire(1'310 * kMs));
  EXPECT_FALSE(feed.feeding());
  EXPECT_FALSE(feed.expire(2'000 * kMs));
  EXPECT_EQ(feed.counters().silences, 1u);
  EXPECT_EQ(feed.counters().sent, 1u);
  // AND a feed that never started never expires
  OdometryFeed idle(OdometryFeedConfig{});
  EXPECT_FALSE(idle.expire(5'000 * kMs));
}

TEST(OdometryFeed, TheResetCounterCountsTheEstimatesRestarts) {
  OdometryFeed feed(OdometryFeedConfig{});
  const std::uint8_t first = feed.onState(tracking(1'000 * kMs, false), 1'000 * kMs)->reset_counter;
  // tracking again after not tracking
  agent::Diagnostics lost = tracking(1'100 * kMs, false);
  lost.stage = agent::Stage::kLost;
  feed.onState(lost, 1'100 * kMs);
  EXPECT_EQ(feed.onState(tracking(1'200 * kMs, false), 1'200 * kMs)->reset_counter, first + 1);
  // the agent's timeline restarted
  agent::Diagnostics resynced = tracking(1'300 * kMs, false);
  resynced.stamp_resyncs = 1;
  EXPECT_EQ(feed.onState(resynced, 1'300 * kMs)->reset_counter, first + 2);
  // nothing new: the same counter
  resynced.stamp_ns = 1'400 * kMs;
  EXPECT_EQ(feed.onState(resynced, 1'400 * kMs)->reset_counter, first + 2);
}

TEST(OdometryWire, Px4GetsNedWithDownUnknownAndTheStandInSeesAPositionAndAVelocity) {
  OdometryFeed feed(OdometryFeedConfig{});
  const Odometry o = *feed.onState(tracking(1'000 * kMs, false), 1'000 * kMs);
  const px4_msgs::msg::VehicleOdometry m = wire::vehicleOdometry(o);
  EXPECT_EQ(m.timestamp_sample(), 1'000'000u);  // [us] on the vehicle's clock
  EXPECT_EQ(m.pose_frame(), 1);                 // NED
  EXPECT_EQ(m.velocity_frame(), 1);
  EXPECT_FLOAT_EQ(m.position()[0], -4.0f);  // north
  EXPECT_FLOAT_EQ(m.position()[1], 3.0f);   // east
  EXPECT_FLOAT_EQ(m.velocity()[0], 0.25f);
  EXPECT_FLOAT_EQ(m.velocity()[1], 0.5f);
  EXPECT_GE(m.position_variance()[2], 1e4f);  // down: no filter trusts it
  EXPECT_TRUE(std::isnan(m.q()[0]));          // the attitude is the vehicle's own
  EXPECT_EQ(m.reset_counter(), o.reset_counter);
  const wire::VisionReport r = wire::visionReportOf(m);
  EXPECT_TRUE(r.position);
  EXPECT_TRUE(r.velocity);
  // AND a NaN position is no position for EKF2
  px4_msgs::msg::VehicleOdometry unknown = m;
  unknown.position()[2] = std::nanf("");
  EXPECT_FALSE(wire::visionReportOf(unknown).position);
}

TEST(OdometryWire, ArdupilotGetsOdomToBaseLinkNorthWestUpStamped0AndTheVehiclesAttitudeTurnedBack) {
  OdometryFeed feed(OdometryFeedConfig{});
  const Odometry o = *feed.onState(tracking(1'000 * kMs, false), 1'000 * kMs);
  const px4::Quaternion attitude = px4::quaternionOf(px4::Euler{0.1, -0.05, 0.7});
  const tf2_msgs::msg::TFMessage m = wire::externalOdometry(o, attitude);
  ASSERT_EQ(m.transforms().size(), 1u);
  const geometry_msgs::msg::TransformStamped& t = m.transforms()[0];
  EXPECT_EQ(t.header().frame_id(), "odom");
  EXPECT_EQ(t.child_frame_id(), "base_link");
  EXPECT_EQ(t.header().stamp().sec(), 0);
  EXPECT_EQ(t.header().stamp().nanosec(), 0u);
  // ArduPilot turns (x, y, z) into NED as (x, -y, -z), (w, x, y, z) as (w, x, -y, -z): what it gets is SWA's
  EXPECT_DOUBLE_EQ(t.transform().translation().x(), -4.0);  // north
  EXPECT_DOUBLE_EQ(-t.transform().translation().y(), 3.0);  // east
  EXPECT_DOUBLE_EQ(-t.transform().translation().z(), 0.0);  // down
  EXPECT_DOUBLE_EQ(t.transform().rotation().w(), attitude.w);
  EXPECT_DOUBLE_EQ(t.transform().rotation().x(), attitude.x);
  EXPECT_DOUBLE_EQ(-t.transform().rotation().y(), attitude.y);
  EXPECT_DOUBLE_EQ(-t.transform().rotation().z(), attitude.z);
  // AND the stand-in reads it back; a transform of another pair is none of ArduPilot's
  const std::optional<wire::ExternalOdomReport> r = wire::externalOdomOf(m);
  ASSERT_TRUE(r);
  EXPECT_EQ(r->stamp_ns, 0);
  EXPECT_DOUBLE_EQ(r->north_m, -4.0);
  EXPECT_DOUBLE_EQ(r->east_m, 3.0);
  tf2_msgs::msg::TFMessage other = m;
  other.transforms()[0].header().frame_id("map");
  EXPECT_FALSE(wire::externalOdomOf(other));
}

}  // namespace
}  // namespace swa::autopilot

// PX4's frames against SWA's (swa/px4/frames.h), with hand-computed cases: every number below follows from the
// conventions written at the top of frames.h, not from the code under test.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include <Eigen/Geometry>

#include "swa/agent/geometry.h"
#include "swa/px4/frames.h"

namespace swa::px4 {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;

Quaternion yawOnly(double yaw) { return {std::cos(yaw / 2), 0.0, 0.0, std::sin(yaw / 2)}; }

SwaAttitude swaOf(const Quaternion& q) { return swaAttitude(eulerOf(q)); }

// The horizontal acceleration the agent reads from a tilt (DESIGN §3.4): q_c R(heading) [pitch; roll], q_c = 1.
agent::Vec2 agentAcceleration(const SwaAttitude& a) {
  return agent::rotation(a.heading_rad) * agent::Vec2(a.pitch_rad, a.roll_rad);
}

// Rotation matrix of a quaternion, to compare rotations rather than angle triples (not unique at the singularity).
Eigen::Matrix3d matrixOf(const Quaternion& q) {
  return Eigen::Quaterniond(q.w, q.x, q.y, q.z).normalized().toRotationMatrix();
}

TEST(Px4Frames, HeadingOfPx4YawIsCounterClockwiseFromEast) {
  // GIVEN level attitudes with PX4 yaw (clockwise from north) 0, 90, 180 and -90 degrees
  // THEN SWA's heading (counter-clockwise from east) is north, east, south and west
  EXPECT_NEAR(swaOf(yawOnly(0.0)).heading_rad, kPi / 2, 1e-12);
  EXPECT_NEAR(swaOf(yawOnly(90 * kDeg)).heading_rad, 0.0, 1e-12);  // heading 90 deg east
  EXPECT_NEAR(swaOf(yawOnly(180 * kDeg)).heading_rad, -kPi / 2, 1e-12);
  EXPECT_NEAR(std::abs(swaOf(yawOnly(-90 * kDeg)).heading_rad), kPi, 1e-12);
  // AND level means no tilt
  EXPECT_NEAR(swaOf(yawOnly(0.3)).roll_rad, 0.0, 1e-12);
  EXPECT_NEAR(swaOf(yawOnly(0.3)).pitch_rad, 0.0, 1e-12);
}

TEST(Px4Frames, HeadingWrapsIntoMinusPiToPi) {
  // GIVEN yaws just either side of south-west and of west, where pi/2 - yaw leaves (-pi, pi]
  for (const double yaw_deg : {-179.0, -91.0, -90.0, 179.0, 181.0, 359.0, -359.0}) {
    const double heading = swaOf(yawOnly(yaw_deg * kDeg)).heading_rad;
    // THEN the heading is wrapped and still points the same way
    EXPECT_GT(heading, -kPi - 1e-12) << yaw_deg;
    EXPECT_LE(heading, kPi + 1e-12) << yaw_deg;
    EXPECT_NEAR(std::cos(heading), std::cos(kPi / 2 - yaw_deg * kDeg), 1e-12) << yaw_deg;
    EXPECT_NEAR(std::sin(heading), std::sin(kPi / 2 - yaw_deg * kDeg), 1e-12) << yaw_deg;
  }
  // -179 deg (PX4) is 269 deg counter-clockwise from east, i.e. -91 deg
  EXPECT_NEAR(swaOf(yawOnly(-179 * kDeg)).heading_rad, -91 * kDeg, 1e-12);
  EXPECT_NEAR(wrapPi(-kPi), kPi, 1e-15);
}

TEST(Px4Frames, NoseDownHeadingNorthAcceleratesNorth) {
  // GIVEN a UAV heading north (PX4 yaw 0) pitched nose-down by 5 degrees (PX4 pitch -5 deg)
  const Quaternion q = quaternionOf({0.0, -5 * kDeg, 0.0});
  EXPECT_NEAR(q.w, std::cos(-2.5 * kDeg), 1e-15);  // a rotation about body y (right) only
  EXPECT_NEAR(q.y, std::sin(-2.5 * kDeg), 1e-15);
  // WHEN the agent reads it
  const SwaAttitude a = swaOf(q);
  // THEN SWA's pitch is +5 deg (forward acceleration), and the acceleration points north (stable +y)
  EXPECT_NEAR(a.pitch_rad, 5 * kDeg, 1e-12);
  const agent::Vec2 acc = agentAcceleration(a);
  EXPECT_NEAR(acc.x(), 0.0, 1e-12);
  EXPECT_GT(acc.y(), 0.08);
}

TEST(Px4Frames, RightSideDownHeadingEastAcceleratesSouth) {
  // GIVEN a UAV heading east (PX4 yaw 90 deg) rolled right side down by 10 degrees (PX4 roll +10 deg)
  const SwaAttitude a = swaOf(quaternionOf({10 * kDeg, 0.0, 90 * kDeg}));
  // THEN it accelerates to its right: south (stable -y); SWA roll is -10 deg (positive is left side down)
  EXPECT_NEAR(a.roll_rad, -10 * kDeg, 1e-12);
  EXPECT_NEAR(a.heading_rad, 0.0, 1e-12);
  const agent::Vec2 acc = agentAcceleration(a);
  EXPECT_NEAR(acc.x(), 0.0, 1e-12);
  EXPECT_LT(acc.y(), -0.17);
}

TEST(Px4Frames, VelocityCommandsBecomeNed) {
  // An SWA command east is NED (0, v, 0); north is (v, 0, 0); vertical speed 0 (altitude held)
  const NedVelocity east = nedOf(agent::Vec2(1.5, 0.0));
  EXPECT_EQ(east.north, 0.0);
  EXPECT_EQ(east.east, 1.5);
  EXPECT_EQ(east.down, 0.0);
  const NedVelocity north = nedOf(agent::Vec2(0.0, -2.0));
  EXPECT_EQ(north.north, -2.0);
  EXPECT_EQ(north.east, 0.0);
  // AND back
  EXPECT_EQ(stableOf(nedOf(agent::Vec2(0.25, -0.75))), agent::Vec2(0.25, -0.75));
}

TEST(Px4Frames, AYawRateIsTheOppositeSignInPx4) {
  // A left turn (counter-clockwise from above, SWA's heading growing) is PX4's yaw falling: yawspeed -0.3
  EXPECT_EQ(yawspeedOf(0.3), -0.3);
  EXPECT_EQ(yawspeedOf(0.0), 0.0);
  EXPECT_EQ(yawRateOf(yawspeedOf(-0.1234567)), -0.1234567);
  // AND it agrees with the attitude conversion: PX4's yaw advanced by yawspeed * dt is SWA's heading advanced by the
  // rate * dt (heading 30 deg, 0.5 s at 0.3 rad/s)
  const double yaw = kPi / 2 - 30 * kDeg;
  const double after = swaOf(yawOnly(yaw + yawspeedOf(0.3) * 0.5)).heading_rad;
  EXPECT_NEAR(after - swaOf(yawOnly(yaw)).heading_rad, 0.3 * 0.5, 1e-12);
}

TEST(Px4Frames, AttitudesRoundTripThroughPx4AndFloat32) {
  // GIVEN seeded attitudes a hovering or manoeuvring multirotor can have
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> tilt(-0.6, 0.6), heading(-kPi, kPi);
  for (int k = 0; k < 1000; ++k) {
    const SwaAttitude in{tilt(rng), tilt(rng), heading(rng)};
    // WHEN they go to PX4's quaternion and back, exactly and through PX4's float32 quaternion
    const Quaternion q = quaternionOf(px4Euler(in));
    const SwaAttitude exact = swaOf(q);
    const Quaternion qf{static_cast<float>(q.w), static_cast<float>(q.x), static_cast<float>(q.y),
                        static_cast<float>(q.z)};
    const SwaAttitude narrow = swaOf(qf);
    // THEN they come back (float32 costs less than 1e-6 rad)
    EXPECT_NEAR(exact.roll_rad, in.roll_rad, 1e-12);
    EXPECT_NEAR(exact.pitch_rad, in.pitch_rad, 1e-12);
    EXPECT_NEAR(std::remainder(exact.heading_rad - in.heading_rad, 2 * kPi), 0.0, 1e-12);
    EXPECT_NEAR(narrow.roll_rad, in.roll_rad, 1e-6);
    EXPECT_NEAR(narrow.pitch_rad, in.pitch_rad, 1e-6);
    EXPECT_NEAR(std::remainder(narrow.heading_rad - in.heading_rad, 2 * kPi), 0.0, 1e-6);
  }
}

TEST(Px4Frames, NearVerticalAttitudesStayFiniteAndKeepTheirRotation) {
  // GIVEN pitch at, just inside and just outside the singular band of +-90 deg, with roll and yaw
  for (const double pitch_deg : {90.0, 89.99, 89.9, -90.0, -89.99, -89.9}) {
    const Euler in{20 * kDeg, pitch_deg * kDeg, 30 * kDeg};
    const Quaternion q = quaternionOf(in);
    // WHEN converted to Euler angles
    const Euler e = eulerOf(q);
    // THEN no NaN, the pitch is right, and the angles describe the same rotation
    EXPECT_TRUE(std::isfinite(e.roll) && std::isfinite(e.pitch) && std::isfinite(e.yaw)) << pitch_deg;
    EXPECT_NEAR(e.pitch, pitch_deg * kDeg, 2e-6) << pitch_deg;
    const double tolerance = std::abs(std::abs(pitch_deg) - 90.0) < 0.06 ? 2e-3 : 1e-9;  // the band costs < 1e-3 rad
    EXPECT_LT((matrixOf(quaternionOf(e)) - matrixOf(q)).cwiseAbs().maxCoeff(), tolerance) << pitch_deg;
  }
  // AND a quaternion a hair beyond the unit sphere at the singularity gives no NaN either
  const Quaternion over{std::sqrt(0.5) + 1e-9, 0.0, std::sqrt(0.5) + 1e-9, 0.0};
  EXPECT_FALSE(std::isnan(eulerOf(over).pitch));
}

TEST(Px4Frames, CorruptQuaternionsAreNotAttitudes) {
  EXPECT_TRUE(isAttitude({1.0, 0.0, 0.0, 0.0}));
  EXPECT_TRUE(isAttitude({0.5, 0.5, 0.5, 0.5 + 1e-7}));  // float32 rounding
  EXPECT_FALSE(isAttitude({0.0, 0.0, 0.0, 0.0}));
  EXPECT_FALSE(isAttitude({1.01, 0.0, 0.0, 0.0}));
  EXPECT_FALSE(isAttitude({std::nan(""), 0.0, 0.0, 1.0}));
  EXPECT_FALSE(isAttitude({std::numeric_limits<double>::infinity(), 0.0, 0.0, 0.0}));
}

TEST(Px4Frames, TimestampsAreTheSameClockInOtherUnits) {
  EXPECT_EQ(stampNsOf(1), std::optional<agent::StampNs>(1000));
  EXPECT_EQ(stampNsOf(1'700'000'000'000'000ULL), std::optional<agent::StampNs>(1'700'000'000'000'000'000LL));
  EXPECT_FALSE(stampNsOf(std::numeric_limits<std::uint64_t>::max()));
  EXPECT_EQ(timestampUsOf(10'000'999), std::optional<std::uint64_t>(10'000));
  EXPECT_FALSE(timestampUsOf(-1));
}

}  // namespace
}  // namespace swa::px4

// Deciding the field order of ArduPilot's IMU quaternion from gravity (swa/autopilot/quaternion_order.h), on messages
// written by the wire layer in either order: at rest at every heading, tilted and noisy; and never while armed, where
// a sinking, tilted multicopter can make the wrong order look level.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <optional>
#include <random>

#include "swa/autopilot/quaternion_order.h"
#include "swa/wire/ardupilot.h"

namespace swa::ardupilot {
namespace {

constexpr double kDeg = M_PI / 180.0;

// Feeds `samples` copies of one IMU message (the attitude, in `layout`, of a vehicle at rest); the decision.
std::optional<QuaternionLayout> decideAtRest(const px4::Quaternion& q, QuaternionLayout layout, int samples,
                                             QuaternionOrderFinder& finder) {
  const sensor_msgs::msg::Imu m = wire::imuMessage(1'000'000u, q, layout);
  std::optional<QuaternionLayout> d;
  for (int k = 0; k < samples; ++k) {
    d = finder.onSample(wire::orientationFieldsOf(m), wire::specificForceOf(m), /*disarmed=*/true);
  }
  return d;
}

// The smallest angle between two headings, in degrees.
double headingGapDeg(double a_deg, double b_deg) { return std::abs(std::remainder(a_deg - b_deg, 360.0)); }

TEST(QuaternionOrder, AtRestEveryHeadingIsDecidedRightOrLeftOpenInItsBlindSpot) {
  for (const QuaternionLayout written : {QuaternionLayout::kRos, QuaternionLayout::kWxyzInXyzw}) {
    // The wrong order looks level at north when ArduPilot writes the ROS order, at south when it writes w, x, y, z
    const double blind_deg = written == QuaternionLayout::kRos ? 0.0 : 180.0;
    for (int heading_deg = -180; heading_deg < 180; heading_deg += 5) {
      QuaternionOrderFinder finder;
      const px4::Quaternion q = px4::quaternionOf(px4::Euler{0.0, 0.0, heading_deg * kDeg});
      // GIVEN a level vehicle at rest WHEN the votes needed have come
      const std::optional<QuaternionLayout> d = decideAtRest(q, written, QuaternionOrderFinder::kVotesNeeded, finder);
      const double gap = headingGapDeg(heading_deg, blind_deg);
      // THEN the order is the one written, or (only near the blind heading) not decided yet; never the other
      if (d) {
        EXPECT_EQ(*d, written) << "heading " << heading_deg;
      } else {
        EXPECT_LE(gap, QuaternionOrderFinder::kDisagreeDeg) << "heading " << heading_deg << " undecided";
      }
      if (gap > QuaternionOrderFinder::kDisagreeDeg) {
        EXPECT_TRUE(d) << "heading " << heading_deg;
      }
    }
  }
}

TEST(QuaternionOrder, OneVoteShortOfTheCountDecidesNothing) {
  QuaternionOrderFinder finder;
  const px4::Quaternion east = px4::quaternionOf(px4::Euler{0.0, 0.0, 90.0 * kDeg});
  EXPECT_FALSE(decideAtRest(east, QuaternionLayout::kRos, QuaternionOrderFinder::kVotesNeeded - 1, finder));
  EXPECT_EQ(decideAtRest(east, QuaternionLayout::kRos, 1, finder), QuaternionLayout::kRos);
}

TEST(QuaternionOrder, ANoisyTiltedVehicleOnTheGroundIsDecidedRight) {
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, 0.05);  // m/s^2, a consumer MEMS accelerometer at rest
  for (const QuaternionLayout written : {QuaternionLayout::kRos, QuaternionLayout::kWxyzInXyzw}) {
    QuaternionOrderFinder finder;
    // GIVEN a vehicle on uneven ground (3 deg roll, -2 deg pitch) facing west, its IMU noisy
    const px4::Quaternion q = px4::quaternionOf(px4::Euler{3.0 * kDeg, -2.0 * kDeg, -90.0 * kDeg});
    const sensor_msgs::msg::Imu m = wire::imuMessage(1'000'000u, q, written);
    const SpecificForce rest = wire::specificForceOf(m);
    std::optional<QuaternionLayout> d;
    for (int k = 0; k < 100 && !d; ++k) {
      d = finder.onSample(wire::orientationFieldsOf(m),
                          SpecificForce{rest.x + noise(rng), rest.y + noise(rng), rest.z + noise(rng)}, true);
    }
    // THEN within a second of samples the written order is found
    EXPECT_EQ(d, std::optional<QuaternionLayout>(written));
  }
}

TEST(QuaternionOrder, AnArmedVehicleIsNoEvidence) {
  // GIVEN ArduPilot writing the ROS order, the vehicle heading north, rolled 20 deg and sinking at 0.6 m/s^2 so that
  // its accelerometer reads exactly g along its own z: read in the other order it looks level, in the right one 20 deg
  // off (a vote for the wrong order, were it counted)
  const px4::Quaternion q = px4::quaternionOf(px4::Euler{20.0 * kDeg, 0.0, 0.0});
  const OrientationFields fields = orientationFieldsOf(q, QuaternionLayout::kRos);
  const SpecificForce thrust{0.0, 0.0, -QuaternionOrderFinder::kGravityMps2};
  EXPECT_LT(
      gravityMismatchDeg(attitudeOf(fields.x, fields.y, fields.z, fields.w, QuaternionLayout::kWxyzInXyzw), thrust),
      QuaternionOrderFinder::kAgreeDeg);
  EXPECT_GT(gravityMismatchDeg(q, thrust), QuaternionOrderFinder::kDisagreeDeg);
  // WHEN it flies so while armed THEN nothing is decided
  QuaternionOrderFinder finder;
  for (int k = 0; k < 1000; ++k) EXPECT_FALSE(finder.onSample(fields, thrust, /*disarmed=*/false));
  EXPECT_EQ(finder.votes(), 0u);
  // AND random armed flight decides nothing either, while the same attitudes at rest on the ground do
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> angle(-M_PI, M_PI), tilt(0.0, 30.0 * kDeg);
  for (int k = 0; k < 2000; ++k) {
    const double t = tilt(rng), dir = angle(rng);
    const px4::Quaternion a = px4::quaternionOf(px4::Euler{t * std::sin(dir), t * std::cos(dir), angle(rng)});
    ASSERT_FALSE(finder.onSample(orientationFieldsOf(a, QuaternionLayout::kRos), thrust, false)) << k;
  }
  EXPECT_EQ(decideAtRest(px4::quaternionOf(px4::Euler{0.0, 0.0, 90.0 * kDeg}), QuaternionLayout::kRos,
                         QuaternionOrderFinder::kVotesNeeded, finder),
            QuaternionLayout::kRos);
}

TEST(QuaternionOrder, BadForcesAreNoEvidence) {
  QuaternionOrderFinder finder;
  const OrientationFields level = orientationFieldsOf(px4::quaternionOf(px4::Euler{0.0, 0.0, 1.0}));
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const SpecificForce f : {SpecificForce{nan, 0.0, -9.8}, SpecificForce{0.0, 0.0, 0.0},
                                SpecificForce{0.0, 0.0, std::numeric_limits<double>::infinity()},
                                SpecificForce{0.0, 0.0, 9.80665}}) {  // upside down, or FLU: no order agrees
    for (int k = 0; k < 100; ++k) EXPECT_FALSE(finder.onSample(level, f, true));
  }
  EXPECT_EQ(finder.votes(), 0u);
  EXPECT_TRUE(std::isnan(gravityMismatchDeg(px4::Quaternion{0.0, 0.0, 0.0, 0.0}, SpecificForce{0.0, 0.0, -9.8})));
}

TEST(QuaternionOrder, AVoteTheOtherWayStartsTheCountAgain) {
  QuaternionOrderFinder finder;
  const px4::Quaternion east = px4::quaternionOf(px4::Euler{0.0, 0.0, 90.0 * kDeg});
  EXPECT_FALSE(decideAtRest(east, QuaternionLayout::kRos, QuaternionOrderFinder::kVotesNeeded - 1, finder));
  EXPECT_FALSE(decideAtRest(east, QuaternionLayout::kWxyzInXyzw, 1, finder));
  EXPECT_EQ(finder.reversals(), 1u);
  EXPECT_FALSE(decideAtRest(east, QuaternionLayout::kRos, QuaternionOrderFinder::kVotesNeeded - 1, finder));
  EXPECT_EQ(decideAtRest(east, QuaternionLayout::kRos, 1, finder), QuaternionLayout::kRos);
  // AND once decided it stays
  EXPECT_EQ(decideAtRest(east, QuaternionLayout::kWxyzInXyzw, 100, finder), QuaternionLayout::kRos);
}

}  // namespace
}  // namespace swa::ardupilot

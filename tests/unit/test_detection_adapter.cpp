// Detections from real detectors (detection_adapter.h): frames placed or refused, covariances used or repaired, ids
// kept or made anonymous, and nothing non-finite or not positive definite ever handed to the agent.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include <Eigen/LU>

#include "swa/agent/detection_adapter.h"

namespace swa::agent::detection_adapter_test {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::array<double, 36> covariance(double xx, double xy, double yx, double yy) {
  std::array<double, 36> c{};
  c[0] = xx;
  c[1] = xy;
  c[6] = yx;
  c[7] = yy;
  c[14] = 1.0;  // z, never read
  return c;
}

ForeignDetectionSet set(std::vector<ForeignDetection> d, const std::string& frame = "uav1/fcu") {
  return {12, 500'000'000u, frame, std::move(d)};
}

DetectionAdapterConfig config() {
  DetectionAdapterConfig c;
  c.frame_ids = {"uav1/fcu", "base_link"};
  return c;
}

// And a detector with its own frame "uav1/lidar", turned by `yaw_rad` in the body.
constexpr const char* kSensorFrame = "uav1/lidar";
DetectionAdapterConfig sensorConfig(double yaw_rad) {
  DetectionAdapterConfig c = config();
  c.sensor_frame_id = kSensorFrame;
  c.sensor_yaw_rad = yaw_rad;
  return c;
}

TEST(DetectionAdapter, ABodyFrameSetKeepsPositionsCovariancesIdsAndItsStamp) {
  DetectionAdapter a(config());
  const auto out = a.convert(set({{10.0, -2.0, 0.5, covariance(0.04, 0.01, 0.01, 0.09), 3, {}}}));
  ASSERT_TRUE(out);
  EXPECT_EQ(out->stamp_ns, 12'500'000'000LL);
  ASSERT_EQ(out->detections.size(), 1u);
  const Detection& d = out->detections[0];
  EXPECT_EQ(d.target_id, 3);
  EXPECT_EQ(d.position_body_m, Vec2(10.0, -2.0));
  ASSERT_TRUE(d.covariance_m2);
  EXPECT_NEAR((*d.covariance_m2)(0, 0), 0.04, 1e-15);
  EXPECT_NEAR((*d.covariance_m2)(0, 1), 0.01, 1e-15);
  EXPECT_NEAR((*d.covariance_m2)(1, 1), 0.09, 1e-15);
}

TEST(DetectionAdapter, ASensorTurnedInTheBodyRotatesPositionAndCovariance) {
  // GIVEN a sensor facing left (+90 deg): its x axis is the body's y
  DetectionAdapterConfig c = sensorConfig(M_PI / 2);
  c.sensor_offset_m = Vec2(0.2, 0.0);
  DetectionAdapter a(c);
  const auto out = a.convert(set({{5.0, 0.0, 0.0, covariance(0.25, 0.0, 0.0, 0.01), std::nullopt, {}}}, kSensorFrame));
  ASSERT_TRUE(out);
  const Detection& d = out->detections[0];
  EXPECT_NEAR(d.position_body_m.x(), 0.2, 1e-12);
  EXPECT_NEAR(d.position_body_m.y(), 5.0, 1e-12);
  // The large variance along the sensor's x is now along the body's y
  EXPECT_NEAR((*d.covariance_m2)(0, 0), 0.01, 1e-12);
  EXPECT_NEAR((*d.covariance_m2)(1, 1), 0.25, 1e-12);
  EXPECT_EQ(d.target_id, kAnonymousId);
  EXPECT_EQ(a.counters().anonymous, 1u);
}

TEST(DetectionAdapter, AFrameItCannotPlaceOrABadStampDropsTheWholeSet) {
  DetectionAdapter a(config());
  const ForeignDetection d{10.0, 0.0, 0.0, std::nullopt, 1, {}};
  EXPECT_FALSE(a.convert(set({d}, "uav1/uvdar_camera_left")));
  EXPECT_FALSE(a.convert(set({d}, "")));
  EXPECT_EQ(a.counters().unknown_frame, 2u);
  EXPECT_FALSE(a.convert({-1, 0, "base_link", {d}}));
  EXPECT_FALSE(a.convert({1, 1'000'000'000u, "base_link", {d}}));
  EXPECT_FALSE(a.convert({std::numeric_limits<std::int64_t>::max(), 0, "base_link", {d}}));
  EXPECT_EQ(a.counters().bad_stamp, 3u);
  EXPECT_EQ(a.counters().sets_out, 0u);
}

TEST(DetectionAdapter, BadOrUnknownCovariancesAreReplacedByTheConfiguredNoiseAndCounted) {
  DetectionAdapter a(config());
  std::vector<ForeignDetection> d;
  for (const auto& c : {covariance(0, 0, 0, 0), covariance(kNaN, 0, 0, 0.1), covariance(0.1, 0.05, -0.05, 0.1),
                        covariance(0.1, 0.2, 0.2, 0.1), covariance(-0.1, 0, 0, 0.1), covariance(1e9, 0, 0, 1e9),
                        covariance(1.0, 0.9999999, 0.9999999, 1.0)}) {
    d.push_back({10.0, 1.0, 0.0, c, 2, {}});
  }
  d.push_back({10.0, 1.0, 0.0, std::nullopt, 2, {}});
  const auto out = a.convert(set(d));
  ASSERT_TRUE(out);
  ASSERT_EQ(out->detections.size(), 8u);  // every detection kept: only its noise is replaced
  for (const Detection& x : out->detections) EXPECT_FALSE(x.covariance_m2);
  EXPECT_EQ(a.counters().covariance_repaired, 6u);  // the last: a fine diagonal, 1e-7 m^2 across its main axis
  EXPECT_EQ(a.counters().covariance_missing, 2u);   // absent, or all zero: unknown, the ROS convention
}

TEST(DetectionAdapter, NonFinitePositionsAreDroppedAndOversizeSetsRefused) {
  DetectionAdapterConfig c = config();
  c.max_detections = 3;
  DetectionAdapter a(c);
  const auto out = a.convert(set({{kNaN, 0, 0, std::nullopt, 1, {}},
                                  {1, INFINITY, 0, std::nullopt, 2, {}},
                                  {7.0, 1.0, kNaN, std::nullopt, 3, {}}}));
  ASSERT_TRUE(out);
  ASSERT_EQ(out->detections.size(), 1u);  // z is not used: a NaN height does not matter
  EXPECT_EQ(out->detections[0].target_id, 3);
  EXPECT_EQ(a.counters().nonfinite_position, 2u);
  EXPECT_FALSE(a.convert(set(std::vector<ForeignDetection>(4, ForeignDetection{1, 1, 0, std::nullopt, 1, {}}))));
  EXPECT_EQ(a.counters().oversize, 1u);
}

TEST(DetectionAdapter, TheSensorsMountAppliesToItsOwnFrameNotTheBodys) {
  // GIVEN a lidar 0.3 m forward, turned 180 deg (it faces back)
  DetectionAdapterConfig c = sensorConfig(M_PI);
  c.sensor_offset_m = Vec2(0.3, 0.0);
  DetectionAdapter a(c);
  const ForeignDetection ahead{4.0, 1.0, 0.0, std::nullopt, 2, {}};
  // WHEN one detection comes in the lidar's frame, the same numbers in the body's
  const auto from_lidar = a.convert(set({ahead}, kSensorFrame));
  const auto from_body = a.convert(set({ahead}, "base_link"));
  // THEN the lidar's is placed behind the vehicle, the body's as it is
  ASSERT_TRUE(from_lidar && from_body);
  EXPECT_NEAR(from_lidar->detections[0].position_body_m.x(), 0.3 - 4.0, 1e-12);
  EXPECT_NEAR(from_lidar->detections[0].position_body_m.y(), -1.0, 1e-12);
  EXPECT_EQ(from_body->detections[0].position_body_m, Vec2(4.0, 1.0));
  // AND without a sensor frame configured, the lidar's frame cannot be placed
  DetectionAdapter body_only(config());
  EXPECT_FALSE(body_only.convert(set({ahead}, kSensorFrame)));
  EXPECT_EQ(body_only.counters().unknown_frame, 1u);
}

TEST(DetectionAdapter, DetectionsOfOtherClassesAreDroppedAndCounted) {
  // GIVEN a clusterer that labels drones "uav" or "drone", and people and unlabelled clusters too
  DetectionAdapterConfig c = config();
  c.classes = splitClasses("uav,,drone");
  ASSERT_EQ(c.classes, (std::vector<std::string>{"uav", "drone"}));
  DetectionAdapter a(c);
  const auto out = a.convert(set({{5.0, 0.0, 0.0, std::nullopt, 1, "uav"},
                                  {6.0, 0.0, 0.0, std::nullopt, 2, "person"},
                                  {7.0, 0.0, 0.0, std::nullopt, 3, "drone"},
                                  {8.0, 0.0, 0.0, std::nullopt, 4, ""},
                                  {9.0, 0.0, 0.0, std::nullopt, 5, std::nullopt}}));
  // THEN the UAVs are kept, and so is a detection with no class at all (UVDAR's): others are dropped and counted
  ASSERT_TRUE(out);
  std::vector<int> ids;
  for (const Detection& d : out->detections) ids.push_back(d.target_id);
  EXPECT_EQ(ids, (std::vector<int>{1, 3, 5}));
  EXPECT_EQ(a.counters().other_class, 2u);
  // AND without a class list every detection is kept
  DetectionAdapter any(config());
  EXPECT_EQ(any.convert(set({{6.0, 0.0, 0.0, std::nullopt, 2, "person"}}))->detections.size(), 1u);
}

TEST(DetectionAdapter, OnlyADecimalStringIsAnId) {
  EXPECT_EQ(numericId("3"), 3);
  EXPECT_EQ(numericId("017"), 17);
  for (const char* s : {"", "uav3", "-1", "3.0", " 3", "1234567890123"}) EXPECT_FALSE(numericId(s)) << s;
}

TEST(DetectionAdapter, RandomDetectorOutputNeverReachesTheAgentNonFiniteOrNotPositiveDefinite) {
  std::mt19937_64 rng(2027);
  std::uniform_real_distribution<double> v(-50.0, 50.0), pick(0.0, 1.0);
  const double specials[] = {kNaN, INFINITY, -INFINITY, 0.0, -1.0, 1e300, 1e-300};
  DetectionAdapter a(sensorConfig(0.3));
  std::size_t detections = 0;
  for (int k = 0; k < 3000; ++k) {
    std::vector<ForeignDetection> d(static_cast<std::size_t>(rng() % 8));
    for (ForeignDetection& x : d) {
      x.x_m = pick(rng) < 0.1 ? specials[rng() % 7] : v(rng);
      x.y_m = pick(rng) < 0.1 ? specials[rng() % 7] : v(rng);
      if (pick(rng) < 0.8) {
        std::array<double, 36> c{};
        for (double& e : c) e = pick(rng) < 0.1 ? specials[rng() % 7] : v(rng) * 1e-3;
        x.covariance = c;
      }
      x.id = pick(rng) < 0.5 ? std::optional<long long>(static_cast<long long>(rng() % 400) - 100) : std::nullopt;
    }
    if (const auto out = a.convert(set(d, kSensorFrame))) {
      for (const Detection& x : out->detections) {
        ++detections;
        ASSERT_TRUE(std::isfinite(x.position_body_m.x()) && std::isfinite(x.position_body_m.y()));
        if (x.covariance_m2) {
          const Mat2& c = *x.covariance_m2;
          ASSERT_TRUE(c.allFinite());
          ASSERT_GT(c(0, 0), 0.0);
          ASSERT_GT(c.determinant(), 0.0);
          ASSERT_GE(0.5 * c.trace() - std::hypot(0.5 * (c(0, 0) - c(1, 1)), c(0, 1)), 1e-6 * (1.0 - 1e-9));
          ASSERT_EQ(c(0, 1), c(1, 0));
        }
        ASSERT_GE(x.target_id, kAnonymousId);
      }
    }
  }
  EXPECT_GT(detections, 5000u);
  EXPECT_GT(a.counters().covariance_repaired, 1000u);
}

}  // namespace
}  // namespace swa::agent::detection_adapter_test

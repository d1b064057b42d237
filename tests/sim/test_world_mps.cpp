// Mutual-perception sensor: body-frame geometry, range, field of view, misses, clutter, IDs, noise, latency.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>
#include <vector>

#include <gtest/gtest.h>

#include "swa/sim/mps_model.h"
#include "swa/sim/world.h"
#include "world_support.h"

namespace swa::sim {
namespace {

using agent::Vec2;

// Noise-free, miss-free sensor on UAVs that hover at their lattice slots, heading east.
Scenario perfectSensing(int n) {
  Scenario s = testing::calmScenario(n, 21);
  s.mps.noise_var_m2 = 0.0;
  s.mps.miss_probability = 0.0;
  return s;
}

std::set<int> targetIds(const agent::DetectionSet& set) {
  std::set<int> ids;
  for (const agent::Detection& d : set.detections) ids.insert(d.target_id);
  return ids;
}

const agent::Detection& detectionOf(const agent::DetectionSet& set, int id) {
  const auto it = std::find_if(set.detections.begin(), set.detections.end(),
                               [id](const agent::Detection& d) { return d.target_id == id; });
  EXPECT_NE(it, set.detections.end()) << "no detection of " << id;
  return *it;
}

// Runs until the next step that delivers detection sets; 10 Hz MPS at 100 Hz dynamics.
void stepToNextScan(World& world) {
  do {
    world.step();
  } while (!world.sensors()[0].detections);
}

TEST(WorldMps, NeighbourStraightAheadOfUavHeadingEastIsAtPlusXBody) {
  // GIVEN UAV 0 at the origin and UAV 1 10 m east, both heading east (psi = 0)
  const World world(perfectSensing(2));
  // THEN at t = 0 UAV 0 sees UAV 1 at +x body, and UAV 1 sees UAV 0 at -x body
  const auto& s0 = world.sensors()[0].detections;
  const auto& s1 = world.sensors()[1].detections;
  ASSERT_TRUE(s0 && s1);
  ASSERT_EQ(s0->detections.size(), 1u);
  EXPECT_EQ(s0->stamp_ns, 0);
  EXPECT_EQ(s0->detections[0].target_id, 1);
  EXPECT_NEAR(s0->detections[0].position_body_m.x(), 10.0, 1e-12);
  EXPECT_NEAR(s0->detections[0].position_body_m.y(), 0.0, 1e-12);
  EXPECT_FALSE(s0->detections[0].covariance_m2.has_value());  // isotropic: the agent applies its R_o
  EXPECT_NEAR(s1->detections[0].position_body_m.x(), -10.0, 1e-12);
}

TEST(WorldMps, DetectionsAreInTheObserversBodyFrameForAnyHeading) {
  // GIVEN 7 UAVs with random headings
  Scenario s = perfectSensing(7);
  s.dynamics.heading = HeadingMode::kRandom;
  World world(s);
  stepToNextScan(world);
  const std::vector<UavTruth>& truth = world.truth();
  for (std::size_t i = 0; i < truth.size(); ++i) {
    const agent::DetectionSet& set = *world.sensors()[i].detections;
    ASSERT_EQ(set.detections.size(), 6u);
    for (const agent::Detection& d : set.detections) {
      // THEN the agent's z_S = R(psi) z_B, added to the observer, lands on the target
      const Vec2 target = truth[i].position_m + agent::rotation(truth[i].heading_rad) * d.position_body_m;
      EXPECT_NEAR((target - truth[static_cast<std::size_t>(d.target_id)].position_m).norm(), 0.0, 1e-9);
    }
  }
  // AND concretely: the neighbour due east of UAV 0 appears at (10 cos psi, -10 sin psi) in its body frame
  const double psi = truth[0].heading_rad;
  const Vec2 z = detectionOf(*world.sensors()[0].detections, 1).position_body_m;
  EXPECT_NEAR(z.x(), 10.0 * std::cos(psi), 1e-9);
  EXPECT_NEAR(z.y(), -10.0 * std::sin(psi), 1e-9);
}

TEST(WorldMps, OnlyUavsWithinRangeAreDetected) {
  // GIVEN a full hexagon (centre + 6 at 10 m; ring neighbours 10, 17.3 and 20 m apart) and a 15 m range
  Scenario s = perfectSensing(7);
  s.mps.range_m = 15.0;
  const World world(s);
  // THEN the centre sees all 6 and each ring UAV the centre and its two ring neighbours
  EXPECT_EQ(targetIds(*world.sensors()[0].detections), (std::set<int>{1, 2, 3, 4, 5, 6}));
  EXPECT_EQ(targetIds(*world.sensors()[1].detections), (std::set<int>{0, 2, 6}));
  EXPECT_EQ(targetIds(*world.sensors()[4].detections), (std::set<int>{0, 3, 5}));
}

TEST(WorldMps, OnlyUavsWithinTheFieldOfViewAreDetected) {
  // GIVEN the hexagon, all heading east; ring slots 1..6 lie at bearings 0, 60, ..., 300 deg from the centre
  Scenario s = perfectSensing(7);
  s.mps.fov_deg = 90.0;
  EXPECT_EQ(targetIds(*World(s).sensors()[0].detections), (std::set<int>{1}));
  s.mps.fov_deg = 180.0;
  EXPECT_EQ(targetIds(*World(s).sensors()[0].detections), (std::set<int>{1, 2, 6}));
  s.mps.fov_deg = 360.0;
  EXPECT_EQ(targetIds(*World(s).sensors()[0].detections), (std::set<int>{1, 2, 3, 4, 5, 6}));
}

TEST(WorldMps, MissRateMatchesMissProbability) {
  // GIVEN 7 UAVs all in range, miss probability 0.05
  Scenario s = perfectSensing(7);
  s.mps.miss_probability = 0.05;
  World world(s);
  // WHEN 1000 scans are taken (42000 chances to detect)
  int chances = 0, detected = 0;
  for (int scan = 0; scan < 1000; ++scan) {
    stepToNextScan(world);
    for (const UavSensors& sensors : world.sensors()) {
      chances += 6;
      detected += static_cast<int>(sensors.detections->detections.size());
    }
  }
  const double miss_rate = 1.0 - static_cast<double>(detected) / chances;
  std::printf("MPS miss rate %.4f over %d chances\n", miss_rate, chances);
  // THEN the miss rate is 0.05 (+-20 % relative; binomial std ~2 %)
  EXPECT_NEAR(miss_rate, 0.05, 0.01);
}

TEST(WorldMps, ClutterIsPoissonAnonymousAndUniformInTheSensingSector) {
  // GIVEN a lone UAV (nothing to detect) with IDs on, 2 false positives per scan, range 40 m, 120 deg field of view
  Scenario s = perfectSensing(1);
  s.mps.clutter_rate = 2.0;
  s.mps.fov_deg = 120.0;
  World world(s);
  // WHEN 4000 scans are taken
  double sum = 0.0, sum2 = 0.0;
  int inner = 0, total = 0;
  for (int scan = 0; scan < 4000; ++scan) {
    stepToNextScan(world);
    const agent::DetectionSet& set = *world.sensors()[0].detections;
    const auto count = static_cast<double>(set.detections.size());
    sum += count;
    sum2 += count * count;
    for (const agent::Detection& d : set.detections) {
      // THEN every false positive is anonymous, even with IDs on, and inside the sensing sector
      EXPECT_EQ(d.target_id, agent::kAnonymousId);
      EXPECT_LE(d.position_body_m.norm(), 40.0 + 1e-9);
      EXPECT_LE(std::abs(std::atan2(d.position_body_m.y(), d.position_body_m.x())), M_PI / 3 + 1e-12);
      inner += d.position_body_m.norm() < 20.0;
      ++total;
    }
  }
  const double mean = sum / 4000.0;
  const double var = sum2 / 4000.0 - mean * mean;
  const double inner_fraction = static_cast<double>(inner) / total;
  std::printf("clutter per scan: mean %.3f variance %.3f, fraction within half range %.3f\n", mean, var,
              inner_fraction);
  // AND the count per scan is Poisson(2): mean 2 (+-5 %), variance = mean (+-15 %)
  EXPECT_NEAR(mean, 2.0, 0.1);
  EXPECT_NEAR(var, 2.0, 0.3);
  // AND it is uniform in area: a quarter falls within half the range
  EXPECT_NEAR(inner_fraction, 0.25, 0.02);
}

TEST(WorldMps, IdsOffMakesEveryDetectionAnonymous) {
  Scenario s = perfectSensing(7);
  s.mps.ids = false;
  const World world(s);
  for (const UavSensors& sensors : world.sensors()) {
    EXPECT_EQ(sensors.detections->detections.size(), 6u);
    EXPECT_EQ(targetIds(*sensors.detections), (std::set<int>{agent::kAnonymousId}));
  }
}

TEST(WorldMps, EmptyScansAreStillDeliveredAtTheMpsRate) {
  // GIVEN a lone UAV without clutter
  World world(perfectSensing(1));
  int sets = 0;
  for (int k = 1; k <= 100; ++k) {
    world.step();
    if (world.sensors()[0].detections) {
      // THEN a set with no detections arrives every 10th step, stamped with its step time
      EXPECT_EQ(k % 10, 0);
      EXPECT_EQ(world.sensors()[0].detections->stamp_ns, world.time_ns());
      EXPECT_TRUE(world.sensors()[0].detections->detections.empty());
      ++sets;
    }
  }
  EXPECT_EQ(sets, 10);
}

TEST(WorldMps, IsotropicNoiseHasTheConfiguredVariance) {
  Scenario s = perfectSensing(2);
  s.mps.noise_var_m2 = 0.1;
  World world(s);
  Vec2 sum2 = Vec2::Zero();
  int n = 0;
  for (int scan = 0; scan < 2000; ++scan) {
    stepToNextScan(world);
    const Vec2 truth_body = world.truth()[1].position_m - world.truth()[0].position_m;  // heading 0
    const Vec2 err = world.sensors()[0].detections->detections.at(0).position_body_m - truth_body;
    sum2 += err.cwiseProduct(err);
    ++n;
  }
  const Vec2 var = sum2 / n;
  std::printf("isotropic MPS noise variance (%.4f, %.4f) m^2\n", var.x(), var.y());
  EXPECT_NEAR(var.x(), 0.1, 0.01);
  EXPECT_NEAR(var.y(), 0.1, 0.01);
}

TEST(WorldMps, RangeBearingNoiseMatchesItsReportedLinearisedCovariance) {
  // GIVEN a target 30 m straight ahead, range std 0.2 m, bearing std 0.01 rad (0.3 m across at 30 m)
  Scenario s = perfectSensing(2);
  s.formation.spacing_m = 30.0;
  s.mps.noise_model = MpsNoiseModel::kRangeBearing;
  World world(s);
  Vec2 sum2 = Vec2::Zero();
  double cross = 0.0;
  int n = 0;
  for (int scan = 0; scan < 3000; ++scan) {
    stepToNextScan(world);
    const agent::Detection& d = world.sensors()[0].detections->detections.at(0);
    const Vec2 truth_body = world.truth()[1].position_m - world.truth()[0].position_m;
    const Vec2 err = d.position_body_m - truth_body;
    sum2 += err.cwiseProduct(err);
    cross += err.x() * err.y();
    ++n;
    // THEN each detection reports the linearised covariance, a valid covariance ~ diag(0.2^2, 0.3^2) here
    ASSERT_TRUE(d.covariance_m2.has_value());
    ASSERT_TRUE(agent::isCovariance(*d.covariance_m2));
    EXPECT_NEAR((*d.covariance_m2)(0, 0), 0.04, 0.002);
    EXPECT_NEAR((*d.covariance_m2)(1, 1), 0.09, 0.005);
  }
  const Vec2 var = sum2 / n;
  std::printf("range/bearing MPS error variance (%.4f, %.4f) m^2, covariance %.5f\n", var.x(), var.y(), cross / n);
  // AND the actual errors have that covariance (+-10 %)
  EXPECT_NEAR(var.x(), 0.04, 0.004);
  EXPECT_NEAR(var.y(), 0.09, 0.009);
  EXPECT_NEAR(cross / n, 0.0, 0.005);
  // AND the covariance formula rotates with the bearing: at 90 deg the range axis is body y
  const agent::Mat2 side = MpsModel::rangeBearingCovariance(30.0, M_PI / 2, 0.2, 0.01);
  EXPECT_NEAR(side(0, 0), 0.09, 1e-12);
  EXPECT_NEAR(side(1, 1), 0.04, 1e-12);
  EXPECT_NEAR(side(0, 1), 0.0, 1e-12);
  // AND it stays positive definite at zero range and zero noise
  EXPECT_TRUE(agent::isCovariance(MpsModel::rangeBearingCovariance(0.0, 0.3, 0.0, 0.0)));
}

TEST(WorldMps, LatencyDelaysDeliveryByExactlyLatencyKeepingTheMeasurementStamp) {
  // GIVEN two worlds alike but for a 0.25 s MPS latency, with noise and misses on
  Scenario s = perfectSensing(4);
  s.mps.noise_var_m2 = 0.1;
  s.mps.miss_probability = 0.05;
  World prompt(s);
  s.mps.latency_s = 0.25;
  World late(s);
  std::vector<agent::DetectionSet> measured;
  int delivered = 0;
  for (int k = 0; k <= 300; ++k) {
    if (k > 0) {
      prompt.step();
      late.step();
    }
    if (prompt.sensors()[2].detections) measured.push_back(*prompt.sensors()[2].detections);
    const auto& got = late.sensors()[2].detections;
    // THEN nothing arrives before 0.25 s
    if (late.time_ns() < 250'000'000) {
      EXPECT_FALSE(got.has_value());
      continue;
    }
    if (!got) continue;
    // AND each set arrives exactly 0.25 s after its stamp, identical to the one measured without latency
    EXPECT_EQ(late.time_ns() - got->stamp_ns, 250'000'000);
    const agent::DetectionSet& original = measured.at(static_cast<std::size_t>(delivered));
    EXPECT_EQ(got->stamp_ns, original.stamp_ns);
    ASSERT_EQ(got->detections.size(), original.detections.size());
    for (std::size_t j = 0; j < original.detections.size(); ++j) {
      EXPECT_EQ(got->detections[j].target_id, original.detections[j].target_id);
      EXPECT_EQ(got->detections[j].position_body_m, original.detections[j].position_body_m);
    }
    ++delivered;
  }
  EXPECT_EQ(delivered, 28);  // scans at 0.0 .. 2.7 s delivered by 3.0 s
}

TEST(WorldMps, LatencyJitterDeliversEverySetOnceWithinItsBoundsSomeOutOfOrder) {
  // GIVEN a world with 0.2 s +- 0.1 s of MPS latency (scans every 0.1 s, so neighbouring scans can swap)
  Scenario s = perfectSensing(4);
  s.mps.latency_s = 0.2;
  s.mps.latency_jitter_s = 0.1;
  World w(s);
  std::vector<agent::StampNs> stamps;
  int out_of_order = 0;
  for (int k = 0; k <= 3000; ++k) {
    if (k > 0) w.step();
    const auto& got = w.sensors()[1].detections;
    if (!got) continue;
    // THEN each set arrives between 0.1 and 0.3 s after its stamp (one 10 ms step of slack: one set per step)
    const agent::StampNs delay_ns = w.time_ns() - got->stamp_ns;
    EXPECT_GE(delay_ns, 100'000'000);
    EXPECT_LE(delay_ns, 310'000'000);
    if (!stamps.empty() && got->stamp_ns < stamps.back()) ++out_of_order;
    stamps.push_back(got->stamp_ns);
  }
  // AND every scan up to 29.7 s is delivered exactly once, none lost or doubled
  std::sort(stamps.begin(), stamps.end());
  EXPECT_EQ(std::adjacent_find(stamps.begin(), stamps.end()), stamps.end());
  for (agent::StampNs t = 0; t <= 29'700'000'000; t += 100'000'000) {
    EXPECT_TRUE(std::binary_search(stamps.begin(), stamps.end(), t)) << "scan at " << t << " ns never arrived";
  }
  // AND some arrive after a later scan: with uniform delays in +-0.1 s, one pair in eight (about 37 of 300) swaps
  EXPECT_GE(out_of_order, 15);
  EXPECT_LE(out_of_order, 70);
}

TEST(WorldMps, JitterMovesOnlyTheArrivalsNotTheOtherSensors) {
  // GIVEN two worlds with 0.2 s of MPS latency, alike but for 0.05 s of jitter in one
  Scenario s = perfectSensing(3);
  s.mps.noise_var_m2 = 0.1;
  s.mps.latency_s = 0.2;
  World plain(s);
  s.mps.latency_jitter_s = 0.05;
  World jittered(s);
  // WHEN both run 5 s
  int plain_sets = 0;
  int differing_arrivals = 0;
  for (int k = 1; k <= 500; ++k) {
    plain.step();
    jittered.step();
    const auto& a = plain.sensors()[0].detections;
    const auto& b = jittered.sensors()[0].detections;
    if (a) {
      ++plain_sets;
      EXPECT_EQ(plain.time_ns() - a->stamp_ns, 200'000'000);
    }
    if (a.has_value() != b.has_value() || (a && b && a->stamp_ns != b->stamp_ns)) ++differing_arrivals;
    const auto& imu_a = plain.sensors()[0].imu;
    const auto& imu_b = jittered.sensors()[0].imu;
    ASSERT_EQ(imu_a.has_value(), imu_b.has_value());
    if (imu_a) {
      EXPECT_EQ(imu_a->pitch_rad, imu_b->pitch_rad);
    }
  }
  // THEN the jitter changes when sets arrive, not what the IMU and GNSS see
  EXPECT_EQ(plain_sets, 49);  // scans at 0.0 .. 4.8 s delivered by 5.0 s
  EXPECT_GT(differing_arrivals, 0);
}

}  // namespace
}  // namespace swa::sim

// Time series and run summary: collisions, drift, end-of-run windows and ANEES.

#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "swa/monitor/accumulator.h"
#include "swa/monitor/chi2.h"
#include "swa/monitor/summary_format.h"
#include "swa/run_record/run_dir.h"

namespace swa::monitor {
namespace {

using agent::Mat2;
using agent::StampNs;
using agent::Vec2;

constexpr StampNs kSecond = 1'000'000'000;

StampNs at(double seconds) { return static_cast<StampNs>(std::llround(seconds * 1e9)); }

// Equilateral triangle of side `side`, first corner at `origin`, all moving at `velocity`.
std::vector<UavTruth> triangle(double side, const Vec2& origin = Vec2::Zero(), const Vec2& velocity = Vec2::Zero()) {
  const std::vector<Vec2> corners{origin, origin + Vec2(side, 0.0),
                                  origin + Vec2(0.5 * side, 0.5 * std::sqrt(3.0) * side)};
  std::vector<UavTruth> uavs;
  for (int i = 0; i < 3; ++i) uavs.push_back({i, corners[static_cast<std::size_t>(i)], velocity, true});
  return uavs;
}

StepInput pairAt(double t, double distance) {
  StepInput s;
  s.stamp_ns = at(t);
  s.uavs = {{0, Vec2(0, 0), Vec2::Zero(), true}, {1, Vec2(distance, 0), Vec2::Zero(), true}};
  return s;
}

TEST(MetricsAccumulator, CollisionOnsetIsCountedOnceWhileThePairStaysClose) {
  // GIVEN a pair approaching, staying in contact (jittering around 1.5 m), leaving, and coming back
  MetricsAccumulator acc;
  const std::vector<double> distance{5.0, 1.0, 1.2, 1.6, 1.4, 1.9, 1.0, 3.0, 1.4, 1.45};
  const std::vector<int> expected_new{0, 1, 0, 0, 0, 0, 0, 0, 1, 0};
  // WHEN the steps are added
  for (std::size_t k = 0; k < distance.size(); ++k) {
    const StepMetrics& m = acc.add(pairAt(0.1 * static_cast<double>(k), distance[k]));
    EXPECT_EQ(m.new_collisions, expected_new[k]) << "step " << k;
  }
  // THEN the first contact is one collision although the pair crossed 1.5 m three times (release at 2.0 m),
  // and the second approach after separating to 3 m is another
  const Summary s = acc.summary();
  EXPECT_EQ(s.collisions, 2u);
  EXPECT_NEAR(s.min_separation_m, 1.0, 1e-12);
}

TEST(MetricsAccumulator, CollisionThresholdIsAParameter) {
  // GIVEN a 2 m collision distance and no hysteresis
  MetricsConfig c;
  c.collision_distance_m = 2.0;
  c.collision_release_m = 0.0;
  MetricsAccumulator acc(c);
  // WHEN the pair sits at 1.9, 2.1, 1.9 m
  acc.add(pairAt(0.0, 1.9));
  acc.add(pairAt(0.1, 2.1));
  acc.add(pairAt(0.2, 1.9));
  // THEN each approach is an onset
  EXPECT_EQ(acc.summary().collisions, 2u);
}

TEST(MetricsAccumulator, ContactWithAUavThatDropsOutEnds) {
  MetricsAccumulator acc;
  acc.add(pairAt(0.0, 1.0));
  StepInput gone = pairAt(0.1, 1.0);
  gone.uavs[1].alive = false;
  acc.add(gone);
  acc.add(pairAt(0.2, 1.0));  // back (e.g. a restarted agent's UAV): a new contact
  EXPECT_EQ(acc.summary().collisions, 2u);
}

TEST(MetricsAccumulator, DriftOfATranslatingSwarmIsItsVelocity) {
  // GIVEN a rigid triangle translating at (0.3, 0.4) m/s, sampled at 10 Hz for 20 s, window from t = 5 s
  MetricsConfig c;
  c.window_start_s = 5.0;
  MetricsAccumulator acc(c);
  const Vec2 v(0.3, 0.4);
  for (int k = 0; k <= 200; ++k) {
    const double t = 0.1 * k;
    StepInput s;
    s.stamp_ns = at(t);
    s.uavs = triangle(10.0, Vec2(50.0, -20.0) + t * v, v);
    const StepMetrics& m = acc.add(s);
    // THEN the time-series drift is NaN until 1 s of history exists, then 0.5 m/s
    if (k < 10) {
      EXPECT_TRUE(std::isnan(m.drift_mps)) << "t = " << t;
    } else {
      EXPECT_NEAR(m.drift_mps, 0.5, 1e-9) << "t = " << t;
    }
  }
  // AND the summary drift over the 15 s window is 0.5 m/s, each UAV moved 7.5 m, the centroid 7.5 m
  const Summary s = acc.summary();
  EXPECT_NEAR(s.window_start_s, 5.0, 1e-12);
  EXPECT_NEAR(s.window_duration_s, 15.0, 1e-12);
  EXPECT_NEAR(s.duration_s, 20.0, 1e-12);
  EXPECT_NEAR(s.drift_velocity_mps, 0.5, 1e-9);
  EXPECT_NEAR(s.drift_speed_max_mps, 0.5, 1e-9);
  EXPECT_NEAR(s.uav_displacement_m, 7.5, 1e-9);
  EXPECT_NEAR(s.centroid_displacement_m, 7.5, 1e-9);
  EXPECT_EQ(s.steps, 201);
  EXPECT_EQ(s.collisions, 0u);
}

TEST(MetricsAccumulator, WindowedDriftAveragesCompleteSixtySecondStretches) {
  // GIVEN a triangle that moves +x at 0.2 m/s for 60 s, back at 0.2 m/s for 60 s, then +y at 0.1 m/s for 70 s,
  // sampled at 10 Hz, window from t = 10 s (so the stretches are [10, 70], [70, 130], [130, 190])
  MetricsConfig c;
  c.window_start_s = 10.0;
  MetricsAccumulator acc(c);
  auto position = [](double t) {
    if (t <= 70.0) return Vec2(0.2 * t, 0.0);
    if (t <= 130.0) return Vec2(14.0 - 0.2 * (t - 70.0), 0.0);
    return Vec2(2.0, 0.1 * (t - 130.0));
  };
  for (int k = 0; k <= 2000; ++k) {
    StepInput s;
    s.stamp_ns = at(0.1 * k);
    s.uavs = triangle(10.0, position(0.1 * k));
    acc.add(s);
  }
  const Summary s = acc.summary();
  // THEN the net drift over the 190 s window is small (|(2, 7) - (2, 0)| / 190) ...
  EXPECT_NEAR(s.drift_velocity_mps, 7.0 / 190.0, 1e-9);
  // ... while the windows see 0.2, 0.2 and 0.1 m/s: the trailing 10 s stretch [190, 200] is left out
  EXPECT_NEAR(s.drift_velocity_windows_mps, (0.2 + 0.2 + 0.1) / 3.0, 1e-9);
}

TEST(MetricsAccumulator, WindowedDriftIsNaNBeforeTheFirstCompleteStretch) {
  MetricsAccumulator acc;
  for (int k = 0; k < 590; ++k) {
    StepInput s;
    s.stamp_ns = at(0.1 * k);
    s.uavs = triangle(10.0, Vec2(0.1 * k, 0.0));
    acc.add(s);
  }
  EXPECT_TRUE(std::isnan(acc.summary().drift_velocity_windows_mps));
  EXPECT_GT(acc.summary().drift_velocity_mps, 0.9);
}

TEST(MetricsAccumulator, HoveringSwarmThatExpandsHasNoDriftButDisplacement) {
  // GIVEN a triangle expanding about its centroid from side 10 to 16 between t = 0 and t = 6 s
  MetricsAccumulator acc;
  for (int k = 0; k <= 60; ++k) {
    const double side = 10.0 + 0.1 * k;
    const Vec2 centre(0.5 * side, 0.5 * side / std::sqrt(3.0));
    StepInput s;
    s.stamp_ns = at(0.1 * k);
    s.uavs = triangle(side, -centre);
    acc.add(s);
  }
  const Summary s = acc.summary();
  // THEN the centroid did not move, but every UAV moved away from it by (16 - 10) / sqrt(3)
  EXPECT_NEAR(s.drift_velocity_mps, 0.0, 1e-12);
  EXPECT_NEAR(s.uav_displacement_m, 6.0 / std::sqrt(3.0), 1e-9);
}

TEST(MetricsAccumulator, UavDroppingOutDoesNotFakeDrift) {
  // GIVEN a static triangle plus a fourth UAV 30 m away that drops out at t = 5 s
  MetricsAccumulator acc;
  for (int k = 0; k <= 100; ++k) {
    StepInput s;
    s.stamp_ns = at(0.1 * k);
    s.uavs = triangle(10.0);
    s.uavs.push_back({3, Vec2(30.0, 30.0), Vec2::Zero(), k < 50});
    acc.add(s);
  }
  // THEN the summary drift, over the UAVs present at both ends, is zero although the centroid jumped
  const Summary s = acc.summary();
  EXPECT_NEAR(s.drift_velocity_mps, 0.0, 1e-12);
  EXPECT_NEAR(s.uav_displacement_m, 0.0, 1e-12);
  EXPECT_EQ(s.uav_count, 3);
  EXPECT_GT(s.drift_speed_max_mps, 1.0);  // the time series does show the jump
}

TEST(MetricsAccumulator, EndValuesAreMeansOverTheLastFiveSeconds) {
  // GIVEN a triangle whose side grows as 10 + t, sampled at 1 Hz for 10 s
  MetricsAccumulator acc;
  for (int k = 0; k <= 10; ++k) {
    StepInput s;
    s.stamp_ns = k * kSecond;
    s.uavs = triangle(10.0 + k);
    acc.add(s);
  }
  const Summary s = acc.summary();
  // THEN d_NB at the end is the mean over t = 5..10 s of 10 + t = 17.5, and the formation error that minus r
  EXPECT_NEAR(s.mean_neighbor_distance_m, 17.5, 1e-12);
  EXPECT_NEAR(s.formation_error_m, 7.5, 1e-12);
  // AND the minimum separation is over the whole run, groups and spread are the last step's
  EXPECT_NEAR(s.min_separation_m, 10.0, 1e-12);
  // (side 20 m >= 1.5 r: no UAV is linked to another, three groups; spread = 20 / sqrt(3))
  EXPECT_EQ(s.groups, 3);
  EXPECT_NEAR(s.spread_m, 20.0 / std::sqrt(3.0), 1e-12);
  EXPECT_EQ(s.uav_count, 3);
}

// Three UAVs in a triangle of side 10, each reporting the other two. Agent i's position estimate is off its truth by
// sqrt(nees_i) sigma along x (unit covariance), its velocity likewise by sqrt(vel_nees_i).
StepInput neesStep(double t, const std::vector<double>& nees_pos, const std::vector<double>& nees_vel) {
  StepInput s;
  s.stamp_ns = at(t);
  s.uavs = triangle(10.0);
  for (int i = 0; i < 3; ++i) {
    EstimateRecord r;
    r.valid = true;
    r.neighbour_count = 2;
    r.neighbour_ids[0] = (i + 1) % 3;
    r.neighbour_ids[1] = (i + 2) % 3;
    r.position_cov_m2 = Mat2::Identity();
    r.velocity_cov_m2ps2 = Mat2::Identity();
    const TruthInFrame truth =
        truthInFloatingFrame(s.uavs[static_cast<std::size_t>(i)], s.uavs, r, FrameVelocity::kNeighbourMean);
    r.position_m = truth.position_m + Vec2(std::sqrt(nees_pos[static_cast<std::size_t>(i)]), 0.0);
    r.velocity_mps = truth.velocity_mps + Vec2(0.0, std::sqrt(nees_vel[static_cast<std::size_t>(i)]));
    s.estimates.push_back(r);
  }
  return s;
}

TEST(MetricsAccumulator, AneesIsTheWindowTimeAverageOfTheStepMeanWithTheChiSquareBand) {
  // GIVEN GNSS lost at t = 5 s; before it the agents' NEES are huge, after it they average 2 (position) and 1
  // (velocity) at every step
  MetricsConfig c;
  c.window_start_s = 5.0;
  MetricsAccumulator acc(c);
  for (int k = 0; k < 50; ++k) acc.add(neesStep(0.1 * k, {100.0, 100.0, 100.0}, {50.0, 50.0, 50.0}));
  for (int k = 50; k <= 150; ++k) {
    const StepMetrics& m = acc.add(neesStep(0.1 * k, {1.0, 3.0, 2.0}, {0.5, 0.5, 2.0}));
    EXPECT_NEAR(m.nees.position, 2.0, 1e-9);
    EXPECT_NEAR(m.nees.velocity, 1.0, 1e-9);
    EXPECT_EQ(m.nees.evaluated, 3);
  }
  // THEN the ANEES counts only the window
  const Summary s = acc.summary();
  EXPECT_NEAR(s.anees_position, 2.0, 1e-9);
  EXPECT_NEAR(s.anees_velocity, 1.0, 1e-9);
  EXPECT_EQ(s.nees_steps, 101);
  EXPECT_EQ(s.nees_samples, 303u);
  // AND the band is that of K = 3 agents with 2 dof: chi2(6) quantiles 1.2373, 14.4494 over 3
  EXPECT_EQ(s.anees_agents, 3);
  const AneesBand band = aneesBand(3, 2, 0.05);
  EXPECT_DOUBLE_EQ(s.anees_band_low, band.low);
  EXPECT_DOUBLE_EQ(s.anees_band_high, band.high);
  EXPECT_NEAR(s.anees_band_low, 1.237344 / 3.0, 1e-6);
  EXPECT_NEAR(s.anees_band_high, 14.449375 / 3.0, 1e-6);
  EXPECT_DOUBLE_EQ(s.anees_position_in_band, 1.0);
  EXPECT_DOUBLE_EQ(s.anees_velocity_in_band, 1.0);
}

TEST(MetricsAccumulator, AneesSkipsAndCountsUnknownNeighbours) {
  // GIVEN one of three agents reporting an anonymous track id in every step
  MetricsAccumulator acc;
  for (int k = 0; k < 10; ++k) {
    StepInput s = neesStep(0.1 * k, {4.0, 2.0, 9.0}, {1.0, 1.0, 1.0});
    s.estimates[2].neighbour_ids[1] = 1'000'000'005;
    acc.add(s);
  }
  const Summary s = acc.summary();
  // THEN its NEES (9) is left out: the mean is over the other two, (4 + 2) / 2, and 10 skips are counted
  EXPECT_NEAR(s.anees_position, 3.0, 1e-9);
  EXPECT_EQ(s.nees_skipped_unknown_id, 10u);
  EXPECT_EQ(s.anees_agents, 2);
  // AND 3 lies in the K = 2 band [chi2(4) 2.5 % / 2, 97.5 % / 2] = [0.242, 5.572]
  EXPECT_DOUBLE_EQ(s.anees_position_in_band, 1.0);
}

TEST(MetricsAccumulator, NoWindowNoEstimatesGiveNaNs) {
  // GIVEN a run that ends before the window starts
  MetricsConfig c;
  c.window_start_s = 100.0;
  MetricsAccumulator acc(c);
  StepInput s;
  s.uavs = triangle(10.0);
  acc.add(s);
  const Summary sum = acc.summary();
  // THEN the window quantities are NaN, the geometry is there
  EXPECT_TRUE(std::isnan(sum.drift_velocity_mps));
  EXPECT_TRUE(std::isnan(sum.window_start_s));
  EXPECT_TRUE(std::isnan(sum.anees_position));
  EXPECT_EQ(sum.anees_agents, 0);
  EXPECT_NEAR(sum.mean_neighbor_distance_m, 10.0, 1e-12);
  // AND an empty accumulator has nothing at all
  const Summary empty = MetricsAccumulator().summary();
  EXPECT_EQ(empty.steps, 0);
  EXPECT_TRUE(std::isnan(empty.mean_neighbor_distance_m));
}

TEST(MetricsAccumulator, BadStepsThrowAndLeaveTheAccumulatorUnchanged) {
  MetricsAccumulator acc;
  acc.add(pairAt(1.0, 1.0));
  // GIVEN a step earlier than the last one, a step with a repeated id, and estimates not matching the UAVs
  EXPECT_THROW(acc.add(pairAt(0.5, 5.0)), std::invalid_argument);
  StepInput twice = pairAt(2.0, 5.0);
  twice.uavs[1].id = 0;
  EXPECT_THROW(acc.add(twice), std::invalid_argument);
  StepInput mismatched = pairAt(2.0, 5.0);
  mismatched.estimates.resize(1);
  EXPECT_THROW(acc.add(mismatched), std::invalid_argument);
  // THEN nothing of them was recorded
  EXPECT_EQ(acc.steps(), 1);
  EXPECT_EQ(acc.summary().collisions, 1u);
  // AND a step at the same stamp is accepted
  EXPECT_NO_THROW(acc.add(pairAt(1.0, 1.0)));
  MetricsConfig bad;
  bad.formation.radius_m = -1.0;
  EXPECT_THROW(MetricsAccumulator{bad}, std::invalid_argument);
}

TEST(MetricsAccumulator, SameInputsGiveTheSameReport) {
  // GIVEN the same run fed to two accumulators
  auto run = [] {
    MetricsAccumulator acc;
    for (int k = 0; k <= 30; ++k) {
      StepInput s = neesStep(0.1 * k, {1.0 + 0.1 * k, 2.0, 0.5}, {1.0, 0.2 * k, 1.0});
      s.uavs[0].position_m += Vec2(0.01 * k * k, -0.02 * k);
      acc.add(s);
    }
    return record::metricsJson(acc.summary()).dump();
  };
  // THEN the summary is identical, byte for byte
  EXPECT_EQ(run(), run());
}

}  // namespace
}  // namespace swa::monitor

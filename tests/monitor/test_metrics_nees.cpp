// Truth in the floating frame and the NEES of the focal estimates against it.

#include <cmath>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "swa/agent/track_bank.h"
#include "swa/monitor/swarm_metrics.h"

namespace swa::monitor {
namespace {

using agent::Mat2;
using agent::Vec2;

constexpr double kRadPerDeg = 3.14159265358979323846 / 180.0;
constexpr double kR = 10.0;

Vec2 onCircle(const Vec2& centre, double deg) {
  const double t = deg * kRadPerDeg;
  return centre + kR * Vec2(std::cos(t), std::sin(t));
}

EstimateRecord recordWith(const std::vector<int>& ids) {
  EstimateRecord r;
  r.valid = true;
  r.formation.radius_m = kR;
  r.formation.circle_fit = agent::CircleFit::kFixedRadius;
  for (int id : ids) r.neighbour_ids[static_cast<std::size_t>(r.neighbour_count++)] = id;
  r.position_cov_m2 = Mat2::Identity();
  r.velocity_cov_m2ps2 = Mat2::Identity();
  return r;
}

// UAV 0 sits at (1, -2) from the centre O = (100, 50) of a circle of radius r through UAVs 1, 2, 3; the neighbours
// translate together at (0.5, 0.2), UAV 0 moves at (1.0, -0.3).
struct Fixture {
  Vec2 centre{100.0, 50.0};
  std::vector<UavTruth> uavs;
  Fixture() {
    uavs.push_back({0, centre + Vec2(1.0, -2.0), Vec2(1.0, -0.3), true});
    uavs.push_back({1, onCircle(centre, 90.0), Vec2(0.5, 0.2), true});
    uavs.push_back({2, onCircle(centre, 210.0), Vec2(0.5, 0.2), true});
    uavs.push_back({3, onCircle(centre, 330.0), Vec2(0.5, 0.2), true});
  }
};

TEST(MetricsTruthFrame, ThreeNeighboursOnACircleGiveTheOffsetFromItsCentre) {
  // GIVEN the fixture (neighbours exactly on a circle of radius r)
  const Fixture f;
  // WHEN the truth is rebuilt with the fixed-radius fit and with the algebraic fit
  const TruthInFrame t = truthInFloatingFrame(f.uavs[0], f.uavs, recordWith({1, 2, 3}), FrameVelocity::kNeighbourMean);
  EstimateRecord alg = recordWith({1, 2, 3});
  alg.formation.circle_fit = agent::CircleFit::kAlgebraic;
  const TruthInFrame a = truthInFloatingFrame(f.uavs[0], f.uavs, alg, FrameVelocity::kNeighbourMean);
  // THEN both put UAV 0 at (1, -2) in the frame, and the velocity relative to the frame is v_0 - v_neighbours
  ASSERT_TRUE(t.ok());
  EXPECT_EQ(t.fit_case, agent::FitCase::kFixedRadius);
  EXPECT_NEAR(t.position_m.x(), 1.0, 1e-9);
  EXPECT_NEAR(t.position_m.y(), -2.0, 1e-9);
  EXPECT_NEAR(t.velocity_mps.x(), 0.5, 1e-12);
  EXPECT_NEAR(t.velocity_mps.y(), -0.5, 1e-12);
  ASSERT_TRUE(a.ok());
  EXPECT_EQ(a.fit_case, agent::FitCase::kAlgebraic);
  EXPECT_NEAR(a.position_m.x(), 1.0, 1e-9);
  EXPECT_NEAR(a.position_m.y(), -2.0, 1e-9);
}

TEST(MetricsTruthFrame, TheWeightedFitWeighsTheTwoNeighboursTheAgentRanksNearest) {
  // GIVEN neighbours off the circle (so the weights matter), the weighted fit, and two records of the same set: one
  // ranking 1 and 2 nearest, one ranking 3 and 1 nearest (as an agent whose estimates order them so would report)
  Fixture f;
  f.uavs[2].position_m += Vec2(0.4, -0.3);
  f.uavs[3].position_m += Vec2(-0.5, 0.2);
  EstimateRecord a = recordWith({1, 2, 3});
  EstimateRecord b = recordWith({3, 1, 2});
  a.formation.far_neighbour_weight = b.formation.far_neighbour_weight = 0.2;
  const TruthInFrame ta = truthInFloatingFrame(f.uavs[0], f.uavs, a, FrameVelocity::kNeighbourMean);
  const TruthInFrame tb = truthInFloatingFrame(f.uavs[0], f.uavs, b, FrameVelocity::kNeighbourMean);
  // THEN each truth is the agent's fit in the record's order on the true positions, and the two frames differ
  ASSERT_TRUE(ta.ok() && tb.ok());
  auto fitIn = [&f](const std::vector<int>& ids) {
    agent::NeighbourPositions p;
    for (int id : ids)
      p.position[static_cast<std::size_t>(p.count++)] =
          f.uavs[static_cast<std::size_t>(id)].position_m - f.uavs[0].position_m;
    return agent::fitFloatingFrame(p, kR, agent::CircleFit::kFixedRadius, 0.2);
  };
  EXPECT_EQ(ta.position_m, -fitIn({1, 2, 3}).centre);
  EXPECT_EQ(tb.position_m, -fitIn({3, 1, 2}).centre);
  EXPECT_GT((ta.position_m - tb.position_m).norm(), 0.01);
}

TEST(MetricsTruthFrame, OneNeighbourFrameIsRFromItTowardsSelf) {
  // GIVEN self at the origin and one neighbour 4 m east: the frame is 6 m west of self (DESIGN §3.3, n = 1)
  const std::vector<UavTruth> uavs{{0, Vec2(0, 0), Vec2::Zero(), true}, {5, Vec2(4, 0), Vec2::Zero(), true}};
  const TruthInFrame t = truthInFloatingFrame(uavs[0], uavs, recordWith({5}), FrameVelocity::kNeighbourMean);
  // THEN self is at +6 m in x in that frame
  ASSERT_TRUE(t.ok());
  EXPECT_NEAR(t.position_m.x(), 6.0, 1e-12);
  EXPECT_NEAR(t.position_m.y(), 0.0, 1e-12);
}

TEST(MetricsTruthFrame, FitDerivativeAgreesWithNeighbourMeanForARigidTranslation) {
  // GIVEN neighbours translating together (the frame moves with them, whatever the fit)
  const Fixture f;
  const TruthInFrame d = truthInFloatingFrame(f.uavs[0], f.uavs, recordWith({1, 2, 3}), FrameVelocity::kFitDerivative);
  // THEN the differentiated fit gives v_0 - v_neighbours too
  ASSERT_TRUE(d.ok());
  EXPECT_FALSE(d.velocity_fallback);
  EXPECT_NEAR(d.velocity_mps.x(), 0.5, 1e-6);
  EXPECT_NEAR(d.velocity_mps.y(), -0.5, 1e-6);
}

TEST(MetricsTruthFrame, FitDerivativeSeesTheFrameFollowSelfAroundASingleNeighbour) {
  // GIVEN self at r from its only neighbour, moving tangentially at 1 m/s, the neighbour at rest
  const std::vector<UavTruth> uavs{{0, Vec2(0, 0), Vec2(0, 1), true}, {1, Vec2(10, 0), Vec2::Zero(), true}};
  const EstimateRecord rec = recordWith({1});
  // WHEN both velocity definitions are evaluated
  const TruthInFrame mean = truthInFloatingFrame(uavs[0], uavs, rec, FrameVelocity::kNeighbourMean);
  const TruthInFrame deriv = truthInFloatingFrame(uavs[0], uavs, rec, FrameVelocity::kFitDerivative);
  // THEN the neighbour-mean approximation says 1 m/s, while the n = 1 frame (r from the neighbour, on the line
  // towards self) stays on top of self: relative velocity 0, which is what the focal filter would see
  EXPECT_NEAR(mean.velocity_mps.y(), 1.0, 1e-12);
  EXPECT_NEAR(deriv.velocity_mps.norm(), 0.0, 1e-6);
}

TEST(MetricsTruthFrame, UnknownNeighbourIdsAreReportedNotGuessed) {
  const Fixture f;
  std::vector<UavTruth> uavs = f.uavs;
  // GIVEN an anonymous track id, an id absent from the truth, self's own id and a dead neighbour
  const auto status = [&uavs, &f](const std::vector<int>& ids) {
    return truthInFloatingFrame(f.uavs[0], uavs, recordWith(ids), FrameVelocity::kNeighbourMean).status;
  };
  EXPECT_EQ(status({1, agent::kFirstAnonymousTrackId}), TruthStatus::kUnknownNeighbour);
  EXPECT_EQ(status({1, 2, 42}), TruthStatus::kUnknownNeighbour);
  EXPECT_EQ(status({0, 1}), TruthStatus::kUnknownNeighbour);
  uavs[3].alive = false;
  EXPECT_EQ(status({1, 2, 3}), TruthStatus::kUnknownNeighbour);
  // AND a record with no neighbours, or a dead self
  EXPECT_EQ(status({}), TruthStatus::kNoNeighbours);
  UavTruth dead_self = f.uavs[0];
  dead_self.alive = false;
  EXPECT_EQ(truthInFloatingFrame(dead_self, f.uavs, recordWith({1}), FrameVelocity::kNeighbourMean).status,
            TruthStatus::kSelfAbsent);
}

TEST(MetricsNees, IsTheMahalanobisNormOfTheError) {
  // GIVEN a diagonal covariance and an error of one sigma on each axis -> 2
  EXPECT_NEAR(nees(Vec2(0.3, -0.4), Mat2(Eigen::Vector2d(0.09, 0.16).asDiagonal())), 2.0, 1e-12);
  // AND a correlated covariance [[2, 1], [1, 2]] with e = (1, 1): P^-1 = [[2, -1], [-1, 2]] / 3 -> 2/3
  Mat2 p;
  p << 2.0, 1.0, 1.0, 2.0;
  EXPECT_NEAR(nees(Vec2(1.0, 1.0), p), 2.0 / 3.0, 1e-12);
  EXPECT_NEAR(nees(Vec2(1.0, -1.0), p), 2.0, 1e-12);
  // AND zero error is zero; a non-covariance or a NaN error gives NaN
  EXPECT_DOUBLE_EQ(nees(Vec2::Zero(), p), 0.0);
  EXPECT_TRUE(std::isnan(nees(Vec2(1, 0), Mat2::Zero())));
  Mat2 indefinite;
  indefinite << 1.0, 2.0, 2.0, 1.0;
  EXPECT_TRUE(std::isnan(nees(Vec2(1, 0), indefinite)));
  EXPECT_TRUE(std::isnan(nees(Vec2(std::nan(""), 0), p)));
}

// All four UAVs of the fixture report the other three. UAV 0's estimate is its truth, UAV 1's is off by one sigma
// on each axis in position and by two sigma on x in velocity; UAV 2 reports an anonymous track; UAV 3 has none.
StepInput mixedStep() {
  const Fixture f;
  StepInput step;
  step.stamp_ns = 1'000'000'000;
  step.uavs = f.uavs;
  step.estimates.resize(4);
  const std::vector<std::vector<int>> ids{{1, 2, 3}, {0, 2, 3}, {0, 1, agent::kFirstAnonymousTrackId + 7}};
  for (std::size_t i = 0; i < 2; ++i) {
    EstimateRecord rec = recordWith(ids[i]);
    const TruthInFrame t = truthInFloatingFrame(f.uavs[i], f.uavs, rec, FrameVelocity::kNeighbourMean);
    rec.position_m = t.position_m;
    rec.velocity_mps = t.velocity_mps;
    step.estimates[i] = rec;
  }
  step.estimates[1].position_m += Vec2(0.3, -0.4);
  step.estimates[1].position_cov_m2 = Eigen::Vector2d(0.09, 0.16).asDiagonal();
  step.estimates[1].velocity_mps += Vec2(0.2, 0.0);
  step.estimates[1].velocity_cov_m2ps2 = 0.01 * Mat2::Identity();
  step.estimates[2] = recordWith(ids[2]);
  step.estimates[3].valid = false;
  return step;
}

TEST(MetricsNees, PerfectEstimateIsZeroAndKnownOffsetIsItsNees) {
  // GIVEN the mixed step
  const StepInput step = mixedStep();
  // WHEN the step NEES is computed
  const NeesStep n = computeNees(step, FrameVelocity::kNeighbourMean);
  // THEN UAV 0 contributes 0 and UAV 1 contributes 2 (position) and 4 (velocity); UAV 2 is skipped for its unknown
  // neighbour id and UAV 3 counted as having no estimate
  EXPECT_EQ(n.evaluated, 2);
  EXPECT_NEAR(n.position, (0.0 + 2.0) / 2.0, 1e-9);
  EXPECT_NEAR(n.velocity, (0.0 + 4.0) / 2.0, 1e-9);
  EXPECT_EQ(n.skipped_unknown_id, 1);
  EXPECT_EQ(n.skipped_invalid, 0);
  EXPECT_EQ(n.no_estimate, 1);
}

TEST(MetricsNees, PerfectEstimateAloneIsExactlyZero) {
  StepInput step = mixedStep();
  step.estimates[1].valid = false;
  const NeesStep n = computeNees(step, FrameVelocity::kNeighbourMean);
  EXPECT_EQ(n.evaluated, 1);
  EXPECT_NEAR(n.position, 0.0, 1e-18);
  EXPECT_NEAR(n.velocity, 0.0, 1e-18);
}

TEST(MetricsNees, UnusableEstimatesAreCountedAsInvalid) {
  // GIVEN the mixed step with UAV 1's covariance made singular, and UAV 3 reporting a NaN position
  StepInput step = mixedStep();
  step.estimates[1].position_cov_m2 = Mat2::Zero();
  step.estimates[3] = recordWith({0, 1, 2});
  step.estimates[3].position_m = Vec2(std::nan(""), 0.0);
  const NeesStep n = computeNees(step, FrameVelocity::kNeighbourMean);
  // THEN both are skipped as invalid and only UAV 0 is evaluated
  EXPECT_EQ(n.evaluated, 1);
  EXPECT_EQ(n.skipped_invalid, 2);
  EXPECT_EQ(n.skipped_unknown_id, 1);
  EXPECT_EQ(n.no_estimate, 0);
  EXPECT_NEAR(n.position, 0.0, 1e-18);
}

TEST(MetricsNees, NoEstimatesGiveNaNAndMismatchedSizesThrow) {
  StepInput step = mixedStep();
  step.estimates.clear();
  const NeesStep n = computeNees(step, FrameVelocity::kNeighbourMean);
  EXPECT_EQ(n.evaluated, 0);
  EXPECT_TRUE(std::isnan(n.position));
  EXPECT_TRUE(std::isnan(n.velocity));
  step.estimates.resize(2);
  EXPECT_THROW(computeNees(step, FrameVelocity::kNeighbourMean), std::invalid_argument);
}

TEST(MetricsNees, DiagnosticsBecomeARecordOnlyWhenTrackingAFloatingFrame) {
  // GIVEN diagnostics of a tracking swa agent with two neighbours
  agent::Diagnostics d;
  d.mode = agent::Mode::kSwa;
  d.stage = agent::Stage::kTracking;
  d.frame_valid = true;
  d.neighbour_count = 2;
  d.neighbour_ids[0] = 4;
  d.neighbour_ids[1] = 2;
  d.position_m = Vec2(0.5, -0.25);
  d.position_cov_m2 = 0.03 * Mat2::Identity();
  agent::FormationConfig formation;
  formation.radius_m = 12.0;
  formation.circle_fit = agent::CircleFit::kAlgebraic;
  // WHEN converted
  const EstimateRecord r = estimateFromDiagnostics(d, formation);
  // THEN the record is valid and carries the estimate, the neighbour ids and the frame parameters
  EXPECT_TRUE(r.valid);
  EXPECT_EQ(r.position_m, d.position_m);
  EXPECT_EQ(r.position_cov_m2, d.position_cov_m2);
  EXPECT_EQ(r.neighbour_count, 2);
  EXPECT_EQ(r.neighbour_ids[1], 2);
  EXPECT_DOUBLE_EQ(r.formation.radius_m, 12.0);
  EXPECT_EQ(r.formation.circle_fit, agent::CircleFit::kAlgebraic);
  // AND not while initialising, lost, without frame, or in standalone mode (take-off frame, not floating)
  agent::Diagnostics lost = d;
  lost.stage = agent::Stage::kLost;
  EXPECT_FALSE(estimateFromDiagnostics(lost, formation).valid);
  agent::Diagnostics no_frame = d;
  no_frame.frame_valid = false;
  EXPECT_FALSE(estimateFromDiagnostics(no_frame, formation).valid);
  agent::Diagnostics standalone = d;
  standalone.mode = agent::Mode::kStandalone;
  EXPECT_FALSE(estimateFromDiagnostics(standalone, formation).valid);
  agent::Diagnostics anchored = d;
  anchored.mode = agent::Mode::kAnchored;
  EXPECT_TRUE(estimateFromDiagnostics(anchored, formation).valid);
}

}  // namespace
}  // namespace swa::monitor

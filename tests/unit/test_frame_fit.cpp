#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include "swa/agent/frame_fit.h"

namespace swa::agent {
namespace {

constexpr double kR = 10.0;

NeighbourPositions make(std::initializer_list<Vec2> pts) {
  NeighbourPositions nb;
  for (const Vec2& p : pts) nb.position[nb.count++] = p;
  return nb;
}

// Neighbours placed exactly on a circle of radius r centred at `centre` (relative to self).
NeighbourPositions onCircle(const Vec2& centre, std::initializer_list<double> angles_deg) {
  NeighbourPositions nb;
  for (double a : angles_deg) {
    const double t = a * M_PI / 180.0;
    nb.position[nb.count++] = centre + kR * Vec2(std::cos(t), std::sin(t));
  }
  return nb;
}

TEST(FrameFit, NoNeighboursGiveNoFrame) {
  const FrameFit f = fitFloatingFrame(NeighbourPositions{}, kR, CircleFit::kFixedRadius);
  EXPECT_FALSE(f.valid);
  EXPECT_EQ(f.fit_case, FitCase::kNone);
}

TEST(FrameFit, OneNeighbourPutsFrameRFromItOnTheLineTowardsSelf) {
  // GIVEN a neighbour 4 m east of self
  // WHEN the frame is fitted
  const FrameFit f = fitFloatingFrame(make({Vec2(4, 0)}), kR, CircleFit::kFixedRadius);
  // THEN the frame is 10 m from the neighbour on the neighbour -> self line, i.e. 6 m west of self
  EXPECT_TRUE(f.valid);
  EXPECT_EQ(f.fit_case, FitCase::kOne);
  EXPECT_NEAR(f.centre.x(), -6.0, 1e-12);
  EXPECT_NEAR(f.centre.y(), 0.0, 1e-12);
  EXPECT_NEAR((f.centre - Vec2(4, 0)).norm(), kR, 1e-12);
}

TEST(FrameFit, TwoNeighboursTakeTheIntersectionCloserToSelf) {
  // GIVEN neighbours at (0, 6) and (0, -6) and self 3 m east of the line between them... shifted: self at origin,
  // neighbours at (-3, 6), (-3, -6): intersections at x = -3 +- 8
  const FrameFit f = fitFloatingFrame(make({Vec2(-3, 6), Vec2(-3, -6)}), kR, CircleFit::kFixedRadius);
  // THEN the closer one (5, 0) is chosen, at exactly r from both
  EXPECT_EQ(f.fit_case, FitCase::kTwo);
  EXPECT_NEAR(f.centre.x(), 5.0, 1e-12);
  EXPECT_NEAR(f.centre.y(), 0.0, 1e-12);
  EXPECT_NEAR((f.centre - Vec2(-3, 6)).norm(), kR, 1e-12);
  EXPECT_NEAR((f.centre - Vec2(-3, -6)).norm(), kR, 1e-12);
  // AND with self on the other side, the other intersection
  const FrameFit g = fitFloatingFrame(make({Vec2(13, 6), Vec2(13, -6)}), kR, CircleFit::kFixedRadius);
  EXPECT_NEAR(g.centre.x(), 5.0, 1e-12);
}

TEST(FrameFit, TwoNeighboursFartherThan2rApartGiveTheirMidpoint) {
  const FrameFit f = fitFloatingFrame(make({Vec2(-15, 2), Vec2(11, 4)}), kR, CircleFit::kFixedRadius);
  EXPECT_EQ(f.fit_case, FitCase::kTwoFarApart);
  EXPECT_NEAR(f.centre.x(), -2.0, 1e-12);
  EXPECT_NEAR(f.centre.y(), 3.0, 1e-12);
}

TEST(FrameFit, ThreeOrMoreOnAnExactCircleAreFittedExactlyByBothMethods) {
  // GIVEN 3..10 neighbours exactly on a circle of radius r centred 2 m north-east of self
  const Vec2 c(2.0, 1.5);
  for (int n = 3; n <= 10; ++n) {
    NeighbourPositions nb;
    for (int j = 0; j < n; ++j) {
      const double t = 0.3 + 2.0 * M_PI * j / n;
      nb.position[nb.count++] = c + kR * Vec2(std::cos(t), std::sin(t));
    }
    // WHEN fitted algebraically and with fixed radius
    const FrameFit alg = fitFloatingFrame(nb, kR, CircleFit::kAlgebraic);
    const FrameFit fr = fitFloatingFrame(nb, kR, CircleFit::kFixedRadius);
    // THEN both recover the centre
    EXPECT_EQ(alg.fit_case, FitCase::kAlgebraic);
    EXPECT_EQ(fr.fit_case, FitCase::kFixedRadius);
    EXPECT_NEAR((alg.centre - c).norm(), 0.0, 1e-9) << "n=" << n;
    EXPECT_NEAR((fr.centre - c).norm(), 0.0, 1e-9) << "n=" << n;
    EXPECT_LE(fr.iterations, 10);
  }
}

TEST(FrameFit, AlgebraicFitIgnoresRadiusSoCompressedNeighboursPullTheFrameIn) {
  // GIVEN three neighbours on a circle of radius 5 (half the desired spacing) through self's side:
  // centre (4, 0), neighbours at angles 60, 180, 300 deg.
  NeighbourPositions nb;
  const Vec2 c(4.0, 0.0);
  for (double a : {180.0, 60.0, 300.0}) {  // nearest first, as selectNeighbours delivers them
    const double t = a * M_PI / 180.0;
    nb.position[nb.count++] = c + 5.0 * Vec2(std::cos(t), std::sin(t));
  }
  // WHEN both methods fit a circle of r = 10
  const FrameFit alg = fitAlgebraic(nb, kR);
  const FrameFit fr = fitFixedRadius(nb, kR);
  // THEN the algebraic centre is the circumcentre of the compressed triangle (r cancels out with c free) ...
  EXPECT_NEAR((alg.centre - c).norm(), 0.0, 1e-9);
  // ... while the fixed-radius fit minimises the radial residuals sum (|p_j - c| - r)^2 instead: at the circumcentre
  // every residual is exactly 5 m (cost 75), the fixed-radius centre does strictly better.
  auto cost = [&](const Vec2& centre) {
    double s = 0.0;
    for (int j = 0; j < nb.count; ++j) s += std::pow((nb.position[j] - centre).norm() - kR, 2);
    return s;
  };
  EXPECT_NEAR(cost(alg.centre), 75.0, 1e-9);
  EXPECT_LT(cost(fr.centre), 0.9 * cost(alg.centre));
  // AND it is a stationary point of that cost (a descent method guarantees first order only: with neighbours
  // compressed to half the spacing the cost has a ring-shaped valley around them, flat to ~1e-8 along the ring).
  const double h = 1e-6;
  const Vec2 grad((cost(fr.centre + Vec2(h, 0)) - cost(fr.centre - Vec2(h, 0))) / (2 * h),
                  (cost(fr.centre + Vec2(0, h)) - cost(fr.centre - Vec2(0, h))) / (2 * h));
  EXPECT_LT(grad.norm(), 1e-5);
}

TEST(FrameFit, FixedRadiusStartsFromTheNearSolutionAndDoesNotMirror) {
  // GIVEN three neighbours spread over a 90 deg arc of an r = 10 circle whose centre is 1 m from self; the mirror
  // circle through the same points lies on the far side of them.
  const NeighbourPositions nb = onCircle(Vec2(1.0, 0.0), {150.0, 180.0, 210.0});
  const FrameFit fr = fitFloatingFrame(nb, kR, CircleFit::kFixedRadius);
  // THEN the near centre is found
  EXPECT_NEAR((fr.centre - Vec2(1.0, 0.0)).norm(), 0.0, 1e-8);
}

TEST(FrameFit, DegenerateSetsGiveDefinedFiniteResults) {
  const NeighbourPositions collinear = make({Vec2(1, 1), Vec2(3, 3), Vec2(6, 6), Vec2(-2, -2)});
  const NeighbourPositions coincident = make({Vec2(5, 5), Vec2(5, 5), Vec2(5, 5)});
  const NeighbourPositions on_self = make({Vec2(0, 0)});
  const NeighbourPositions pair_on_self = make({Vec2(0, 0), Vec2(0, 0)});
  const NeighbourPositions far = make({Vec2(1e5, 0), Vec2(-1e5, 1), Vec2(0, 1e5)});
  const NeighbourPositions tiny = make({Vec2(1e-12, 0), Vec2(0, 1e-12), Vec2(-1e-12, 0)});
  for (CircleFit m : {CircleFit::kAlgebraic, CircleFit::kFixedRadius}) {
    for (const NeighbourPositions* nb : {&collinear, &coincident, &on_self, &pair_on_self, &far, &tiny}) {
      const FrameFit f = fitFloatingFrame(*nb, kR, m);
      EXPECT_TRUE(f.valid);
      EXPECT_TRUE(std::isfinite(f.centre.x()) && std::isfinite(f.centre.y()));
    }
  }
  // Collinear with the algebraic fit falls back to the n = 2 solution of the two nearest, by design.
  const FrameFit col = fitFloatingFrame(collinear, kR, CircleFit::kAlgebraic);
  EXPECT_EQ(col.fit_case, FitCase::kCollinearFallback);
  const FrameFit two = fitTwo(collinear.position[0], collinear.position[1], kR);
  EXPECT_NEAR((col.centre - two.centre).norm(), 0.0, 1e-12);
  // Coincident neighbours: the documented direction (-x from the neighbour).
  const FrameFit coin = fitFloatingFrame(coincident, kR, CircleFit::kFixedRadius);
  EXPECT_EQ(coin.fit_case, FitCase::kCoincident);
  EXPECT_NEAR((coin.centre - Vec2(5, 5)).norm(), kR, 1e-9);
}

TEST(FrameFit, RandomNoisyInputsNeverProduceNaN) {
  // GIVEN 1e4 seeded random neighbour sets of 1..10 points, some clustered to within micrometres
  std::mt19937_64 rng(7);
  std::uniform_int_distribution<int> count(1, 10);
  std::uniform_real_distribution<double> pos(-40.0, 40.0);
  std::uniform_real_distribution<double> scale_exp(-6.0, 0.0);
  int bad = 0;
  for (int trial = 0; trial < 10000; ++trial) {
    NeighbourPositions nb;
    nb.count = count(rng);
    const double s = std::pow(10.0, scale_exp(rng));
    for (int j = 0; j < nb.count; ++j) nb.position[j] = Vec2(pos(rng), pos(rng)) * s;
    for (CircleFit m : {CircleFit::kAlgebraic, CircleFit::kFixedRadius}) {
      const FrameFit f = fitFloatingFrame(nb, kR, m);
      if (!f.valid || !f.centre.allFinite()) ++bad;
    }
  }
  EXPECT_EQ(bad, 0);
}

// ---------------------------------------------------------------------------------------------------------------
// Weighted fixed-radius fit: the two nearest neighbours weigh 1, the rest far_weight (DESIGN §3.3).

double weightedCost(const NeighbourPositions& nb, const Vec2& c, double far_weight) {
  double s = 0.0;
  for (int j = 0; j < nb.count; ++j) s += (j < 2 ? 1.0 : far_weight) * std::pow((nb.position[j] - c).norm() - kR, 2);
  return s;
}

TEST(WeightedFit, NeighboursOnTheCircleGiveItsCentreForEveryWeight) {
  // GIVEN four neighbours exactly on an r-circle round (0.7, -0.4), nearest first
  const NeighbourPositions nb = onCircle(Vec2(0.7, -0.4), {170.0, 115.0, 230.0, 60.0});
  for (double w : {1.0, 0.2, 0.01}) {
    // THEN the fit recovers the centre, whatever the weight
    EXPECT_NEAR((fitFixedRadius(nb, kR, w).centre - Vec2(0.7, -0.4)).norm(), 0.0, 1e-8) << "w = " << w;
  }
}

TEST(WeightedFit, WeightOneIsTheUnweightedFitAndTinyWeightTheTwoNearestPoint) {
  // GIVEN a second-shell neighbour at sqrt(3) r besides two first-shell neighbours of a triangular lattice
  const NeighbourPositions nb =
      make({Vec2(kR, 0), Vec2(0.5 * kR, std::sqrt(0.75) * kR), Vec2(1.5 * kR, std::sqrt(0.75) * kR)});
  // THEN far_weight = 1 is bit for bit the unweighted fit ...
  const FrameFit unweighted = fitFixedRadius(nb, kR);
  EXPECT_EQ(fitFixedRadius(nb, kR, 1.0).centre, unweighted.centre);
  // ... and a vanishing weight leaves the two-nearest solution, which is the lattice node itself (self at the
  // origin is already r from both): the far neighbour no longer pulls
  const FrameFit nearly_two = fitFixedRadius(nb, kR, 1e-9);
  const FrameFit two = fitTwo(nb.position[0], nb.position[1], kR);
  EXPECT_NEAR((nearly_two.centre - two.centre).norm(), 0.0, 1e-6);
  EXPECT_NEAR(two.centre.norm(), 0.0, 1e-9);
}

TEST(WeightedFit, FarNeighbourPullsFiveTimesLessAtWeightPointTwo) {
  // GIVEN the same lattice corner: self at a node (the true frame centre is self, 0), two neighbours at r and the
  // second-shell node at sqrt(3) r that k = 3 would fit
  const NeighbourPositions nb =
      make({Vec2(kR, 0), Vec2(0.5 * kR, std::sqrt(0.75) * kR), Vec2(1.5 * kR, std::sqrt(0.75) * kR)});
  // WHEN fitted unweighted and with the reference weight 0.2
  const FrameFit unweighted = fitFixedRadius(nb, kR, 1.0);
  const FrameFit weighted = fitFixedRadius(nb, kR, 0.2);
  // THEN both move the frame towards the far node (that is the squeeze of DESIGN §3.2) but the weighted one much
  // less: measured 3.37 m unweighted, 0.89 m weighted (0.27x; the pull is not linear in the weight)
  const double pull_unweighted = unweighted.centre.norm(), pull_weighted = weighted.centre.norm();
  std::cout << "pull of the second-shell node: unweighted " << pull_unweighted << " m, weighted " << pull_weighted
            << " m\n";
  EXPECT_GT(pull_unweighted, 1.5);
  EXPECT_LT(pull_weighted, 0.4 * pull_unweighted);
  // AND the weighted centre is a local minimum of the weighted cost (no point within 1 cm does better)
  const double at = weightedCost(nb, weighted.centre, 0.2);
  for (int k = 0; k < 16; ++k) {
    const double a = k * M_PI / 8;
    EXPECT_GE(weightedCost(nb, weighted.centre + 0.01 * Vec2(std::cos(a), std::sin(a)), 0.2), at - 1e-12);
  }
}

TEST(WeightedFit, FloatingFramePassesTheWeightToTheFixedRadiusFitOnly) {
  const NeighbourPositions nb =
      make({Vec2(kR, 0), Vec2(0.5 * kR, std::sqrt(0.75) * kR), Vec2(1.5 * kR, std::sqrt(0.75) * kR)});
  EXPECT_EQ(fitFloatingFrame(nb, kR, CircleFit::kFixedRadius, 0.2).centre, fitFixedRadius(nb, kR, 0.2).centre);
  // The algebraic fit has no weights: the paper's literal method stays literal
  EXPECT_EQ(fitFloatingFrame(nb, kR, CircleFit::kAlgebraic, 0.2).centre, fitAlgebraic(nb, kR).centre);
}

// Gradient of the weighted cost (halved) at c: zero at the fit's optimum.
Vec2 weightedGradient(const NeighbourPositions& nb, const Vec2& c, double far_weight) {
  Vec2 g = Vec2::Zero();
  for (int j = 0; j < nb.count; ++j) {
    const Vec2 d = nb.position[j] - c;
    g -= (j < 2 ? 1.0 : far_weight) * (d.norm() - kR) * d.normalized();
  }
  return g;
}

TEST(WeightedFit, ReachesTheOptimumOfANoisyLatticeInAFewIterations) {
  // GIVEN 2000 seeded neighbourhoods of an interior UAV: 3-6 of the six lattice neighbours at r, each displaced by
  // 0.3 m, self 0.5 m off its node, sorted nearest first. The residuals do not vanish at the optimum, where plain
  // Gauss-Newton converges only linearly (16 iterations on average, a quarter of the fits stopped at the cap)
  std::mt19937_64 rng(11);
  std::normal_distribution<double> noise(0.0, 0.3);
  std::uniform_real_distribution<double> turn(0.0, 2.0 * M_PI);
  std::uniform_int_distribution<int> count(3, 6);
  int worst_iterations = 0, iterations = 0;
  double worst_gradient = 0.0;
  const int trials = 2000;
  for (int trial = 0; trial < trials; ++trial) {
    const Vec2 self_offset(0.5 * noise(rng) / 0.3, 0.5 * noise(rng) / 0.3);
    const double t0 = turn(rng);
    NeighbourPositions nb;
    nb.count = count(rng);
    for (int j = 0; j < nb.count; ++j) {
      const double t = t0 + j * M_PI / 3.0;
      nb.position[j] = kR * Vec2(std::cos(t), std::sin(t)) + Vec2(noise(rng), noise(rng)) - self_offset;
    }
    std::sort(nb.position.begin(), nb.position.begin() + nb.count,
              [](const Vec2& a, const Vec2& b) { return a.norm() < b.norm(); });
    // WHEN fitted with the reference weight
    const FrameFit f = fitFixedRadius(nb, kR, 0.2);
    ASSERT_EQ(f.fit_case, FitCase::kFixedRadius);
    worst_iterations = std::max(worst_iterations, f.iterations);
    iterations += f.iterations;
    worst_gradient = std::max(worst_gradient, weightedGradient(nb, f.centre, 0.2).norm());
  }
  std::cout << "iterations: mean " << static_cast<double>(iterations) / trials << ", worst " << worst_iterations
            << "; worst gradient " << worst_gradient << " m\n";
  // THEN every fit stops on a stationary point of the weighted cost (a gradient of tens of nanometres: below that the
  // cost no longer decreases in double precision) well before the cap
  EXPECT_LT(worst_gradient, 1e-7);
  EXPECT_LE(worst_iterations, 10);
  EXPECT_LT(static_cast<double>(iterations) / trials, 6.0);
}

}  // namespace
}  // namespace swa::agent

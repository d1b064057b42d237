#include <cmath>
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
  // AND it is a stationary point of that cost (Gauss-Newton guarantees first order only: with neighbours compressed
  // to half the spacing the cost has a ring-shaped valley around them, flat to ~1e-8 along the ring).
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

}  // namespace
}  // namespace swa::agent

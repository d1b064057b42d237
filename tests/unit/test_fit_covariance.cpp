// The frame fit's covariance (frame_fit.h: fitCovariance) against the spread of the fit itself over noisy
// neighbours: the first-order propagation must match a seeded Monte Carlo of the same geometry.

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "swa/agent/frame_fit.h"

namespace swa::agent::fit_covariance_test {
namespace {

constexpr double kR = 10.0;
constexpr double kFarWeight = 0.2;
constexpr int kDraws = 20000;

Vec2 polar(double d, double deg) {
  const double a = deg * M_PI / 180.0;
  return d * Vec2(std::cos(a), std::sin(a));
}

struct Spread {
  Mat2 predicted;
  Mat2 sampled;
};

// Neighbours at `centre + polar(r, angle)` (self at the origin), each with its own covariance; the fit's centre over
// kDraws noisy copies, seeded.
Spread spreadOf(const Vec2& centre, const std::vector<double>& angles, const std::vector<Mat2>& covs) {
  NeighbourPositions nb;
  NeighbourCovariances cov{};
  for (std::size_t j = 0; j < angles.size(); ++j) {
    nb.position[nb.count++] = centre + polar(kR, angles[j]);
    cov[j] = covs[j];
  }
  const FrameFit fit = fitFloatingFrame(nb, kR, CircleFit::kFixedRadius, kFarWeight);
  Spread s;
  EXPECT_TRUE(fitCovariance(nb, cov, fit, kR, kFarWeight, s.predicted));
  std::mt19937_64 rng(7);
  std::normal_distribution<double> n01;
  Vec2 sum = Vec2::Zero();
  Mat2 sq = Mat2::Zero();
  for (int k = 0; k < kDraws; ++k) {
    NeighbourPositions noisy = nb;
    for (int j = 0; j < nb.count; ++j) {
      const Eigen::LLT<Mat2> llt(cov[static_cast<std::size_t>(j)]);
      noisy.position[static_cast<std::size_t>(j)] += llt.matrixL() * Vec2(n01(rng), n01(rng));
    }
    const Vec2 c = fitFloatingFrame(noisy, kR, CircleFit::kFixedRadius, kFarWeight).centre;
    sum += c;
    sq += c * c.transpose();
  }
  const Vec2 mean = sum / kDraws;
  s.sampled = sq / kDraws - mean * mean.transpose();
  return s;
}

// Relative agreement in the matrix norm: first order is exact only as the noise goes to zero.
void expectClose(const Spread& s, double tolerance) {
  EXPECT_LE((s.predicted - s.sampled).norm(), tolerance * s.sampled.norm()) << "predicted\n"
                                                                            << s.predicted << "\nsampled\n"
                                                                            << s.sampled;
}

TEST(FitCovariance, OneNeighbourMatchesTheFitsSpread) {
  const Spread s = spreadOf(Vec2(-3.0, 1.0), {18.0}, {Mat2::Identity() * 0.05});
  expectClose(s, 0.05);
}

TEST(FitCovariance, OneNeighbourAtTheRadiusPassesOnlyItsRadialError) {
  // GIVEN self at the frame origin (the neighbour exactly r away)
  const Spread s = spreadOf(Vec2::Zero(), {18.0}, {Mat2::Identity() * 0.05});
  // THEN the neighbour's tangential error does not move the centre, its radial error moves it one to one
  const Vec2 radial = polar(1.0, 18.0);
  const Vec2 tangent = polar(1.0, 108.0);
  EXPECT_NEAR(radial.dot(s.predicted * radial), 0.05, 1e-12);
  EXPECT_NEAR(tangent.dot(s.predicted * tangent), 0.0, 1e-12);
  EXPECT_NEAR(radial.dot(s.sampled * radial), 0.05, 0.05 * 0.05);
}

TEST(FitCovariance, TwoNeighboursMatchTheIntersectionsSpread) {
  const Spread s = spreadOf(Vec2(2.0, -1.0), {100.0, 200.0}, {Mat2::Identity() * 0.05, Mat2::Identity() * 0.02});
  expectClose(s, 0.05);
}

TEST(FitCovariance, SixWeightedNeighboursMatchTheFitsSpreadAndBeatTwo) {
  // GIVEN six neighbours (the lattice interior) with anisotropic covariances
  Mat2 a;
  a << 0.06, 0.01, 0.01, 0.03;
  const std::vector<double> six{0.0, 60.0, 120.0, 180.0, 240.0, 300.0};
  const Spread s = spreadOf(Vec2(0.5, 0.3), six, std::vector<Mat2>(6, a));
  expectClose(s, 0.05);
  // AND the fit is known better than from its two nearest alone
  const Spread two = spreadOf(Vec2(0.5, 0.3), {0.0, 60.0}, std::vector<Mat2>(2, a));
  EXPECT_LT(s.predicted.trace(), two.predicted.trace());
}

TEST(FitCovariance, TwoNeighboursInLineWithTheCentreLeaveItUnknownAcross) {
  // GIVEN two neighbours 2r - 2 mm apart: their circles of radius r barely intersect, at points close to the
  // line between them
  NeighbourPositions nb;
  nb.position[nb.count++] = Vec2(-0.001, 0.1);
  nb.position[nb.count++] = Vec2(-19.999, 0.1);
  NeighbourCovariances cov{};
  cov[0] = cov[1] = Mat2::Identity() * 0.05;
  const FrameFit fit = fitFloatingFrame(nb, kR, CircleFit::kFixedRadius, kFarWeight);
  Mat2 out;
  ASSERT_TRUE(fitCovariance(nb, cov, fit, kR, kFarWeight, out));
  // THEN the variance across the line is orders of magnitude above the neighbours' own
  EXPECT_GT(out(1, 1), 100.0 * 0.05);
  EXPECT_TRUE(out.allFinite());
}

TEST(FitCovariance, TheAlgebraicFitHasNoModelAndSaysSo) {
  NeighbourPositions nb;
  for (double a : {0.0, 120.0, 240.0}) nb.position[nb.count++] = polar(kR, a);
  NeighbourCovariances cov{};
  cov.fill(Mat2::Identity() * 0.05);
  const FrameFit fit = fitFloatingFrame(nb, kR, CircleFit::kAlgebraic);
  Mat2 out;
  EXPECT_FALSE(fitCovariance(nb, cov, fit, kR, 1.0, out));
}

}  // namespace
}  // namespace swa::agent::fit_covariance_test

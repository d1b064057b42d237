#include <random>

#include <gtest/gtest.h>
#include <Eigen/Eigenvalues>

#include "swa/agent/lkf.h"
#include "swa/agent/pva_model.h"

namespace swa::agent {
namespace {

TEST(Lkf, OnePredictAndCorrectMatchHandComputation) {
  // GIVEN a constant-velocity filter x = [p v] at [1 1], P = I, Q = 0.1 I, dt = 1
  using F2 = Lkf<2, 1>;
  StateCov<2> s;
  s.x << 1.0, 1.0;
  s.P.setIdentity();
  Eigen::Matrix2d F;
  F << 1, 1, 0, 1;
  const Eigen::Matrix2d Q = 0.1 * Eigen::Matrix2d::Identity();

  // WHEN it predicts one step and corrects with position z = 3, R = 0.9
  F2::predict(s, F, Q);
  // THEN the prior is x = [2 1], P = F P F' + Q = [[2.1 1] [1 1.1]]
  EXPECT_DOUBLE_EQ(s.x(0), 2.0);
  EXPECT_DOUBLE_EQ(s.x(1), 1.0);
  EXPECT_NEAR(s.P(0, 0), 2.1, 1e-12);
  EXPECT_NEAR(s.P(0, 1), 1.0, 1e-12);
  EXPECT_NEAR(s.P(1, 1), 1.1, 1e-12);

  Eigen::Matrix<double, 1, 2> H;
  H << 1, 0;
  Innovation<1> in;
  ASSERT_TRUE(F2::correct<1>(s, H, Eigen::Matrix<double, 1, 1>(3.0), Eigen::Matrix<double, 1, 1>(0.9), &in));
  // S = 3, K = [0.7 1/3], y = 1: x = [2.7 4/3]; P = P - K H P
  EXPECT_NEAR(in.S(0, 0), 3.0, 1e-12);
  EXPECT_NEAR(in.y(0), 1.0, 1e-12);
  EXPECT_NEAR(in.mahalanobis2, 1.0 / 3.0, 1e-12);
  EXPECT_NEAR(s.x(0), 2.7, 1e-12);
  EXPECT_NEAR(s.x(1), 4.0 / 3.0, 1e-12);
  EXPECT_NEAR(s.P(0, 0), 0.63, 1e-12);
  EXPECT_NEAR(s.P(0, 1), 0.3, 1e-12);
  EXPECT_NEAR(s.P(1, 0), 0.3, 1e-12);
  EXPECT_NEAR(s.P(1, 1), 1.1 - 1.0 / 3.0, 1e-12);
}

TEST(Lkf, PredictWithInputAddsBu) {
  // GIVEN the damped focal model at rest, dt = 0.01 s, tau = 2.8 s
  PvaState s;
  s.P = PvaMat::Identity();
  const double dt = 0.01, e_d = std::exp(-dt / 2.8);
  Eigen::Matrix<double, 6, 2> B = Eigen::Matrix<double, 6, 2>::Zero();
  B.block<2, 2>(pva::Vel::offset, 0) = Mat2::Identity() * (1.0 - e_d);
  // WHEN it predicts with u = [1, -2]
  Pva::predict(s, pvaTransition(dt, e_d), B, Vec2(1.0, -2.0), PvaMat::Zero());
  // THEN only the velocity moves, by (1 - e_d) u
  EXPECT_NEAR(segment<pva::Vel>(s.x).x(), 1.0 - e_d, 1e-15);
  EXPECT_NEAR(segment<pva::Vel>(s.x).y(), -2.0 * (1.0 - e_d), 1e-15);
  EXPECT_EQ(segment<pva::Pos>(s.x), Vec2::Zero());
}

TEST(Lkf, CovarianceStaysSymmetricPositiveDefiniteOver1e5RandomSteps) {
  // GIVEN the 6-state model and a seeded stream of random steps, noise levels and measurements spanning 9 decades
  std::mt19937_64 rng(20261121);
  std::uniform_real_distribution<double> dt_dist(1e-4, 0.5);
  std::uniform_real_distribution<double> log_r(-6.0, 3.0);
  std::normal_distribution<double> z_dist(0.0, 50.0);
  std::bernoulli_distribution position_meas(0.3);
  PvaState s;
  const PvaNoise q{1e-3, 1e-2, 1e-1, 0.01};
  double min_eig = 1e300;
  double max_asym = 0.0;

  // WHEN it runs 1e5 predict/correct cycles alternating position and acceleration corrections
  for (int k = 0; k < 100000; ++k) {
    const double dt = dt_dist(rng);
    Pva::predict(s, pvaTransition(dt, std::exp(-dt / 2.8)), pvaProcessNoise(q, dt));
    const Mat2 R = Mat2::Identity() * std::pow(10.0, log_r(rng));
    const Vec2 z(z_dist(rng), z_dist(rng));
    const auto H = position_meas(rng) ? positionObservation() : accelerationObservation();
    ASSERT_TRUE(Pva::correct<2>(s, H, z, R)) << "step " << k;
    max_asym = std::max(max_asym, (s.P - s.P.transpose()).cwiseAbs().maxCoeff());
    if (k % 1000 == 0 || k == 99999) {
      min_eig = std::min(min_eig, Eigen::SelfAdjointEigenSolver<PvaMat>(s.P).eigenvalues().minCoeff());
    }
  }

  // THEN P is exactly symmetric, positive definite and finite throughout
  EXPECT_EQ(max_asym, 0.0);
  EXPECT_GT(min_eig, 0.0);
  EXPECT_TRUE(s.P.allFinite());
  EXPECT_TRUE(s.x.allFinite());
}

TEST(Lkf, CorrectionWithNonPositiveInnovationCovarianceIsRefused) {
  // GIVEN a state with zero covariance and a measurement claiming negative noise
  PvaState s;
  s.P.setZero();
  const PvaState before = s;
  // WHEN corrected with R = -1
  const bool ok = Pva::correct<2>(s, positionObservation(), Vec2(1, 1), Mat2::Identity() * -1.0);
  // THEN nothing changes
  EXPECT_FALSE(ok);
  EXPECT_EQ(s.x, before.x);
  EXPECT_EQ(s.P, before.P);
}

}  // namespace
}  // namespace swa::agent

// Paper eq. 20–22: the whole swarm, observed only through relative positions, is unobservable exactly along a
// common translation and a common velocity (4 directions), and one absolute fix removes all four. This is why the
// agent estimates in a floating frame and why the `anchored` mode needs only one GNSS-equipped member.

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

constexpr double kDt = 0.01;  // the 100 Hz prediction step of the paper

// Per-UAV state [x, y, vx, vy]; UAV i occupies columns 4i .. 4i+3.
Index posCol(int uav) { return 4 * static_cast<Index>(uav); }

// F_c = blockdiag([I2, dt I2; 0, I2]) — constant-velocity lateral motion of every UAV.
MatrixXd swarmTransition(int n) {
  MatrixXd f = MatrixXd::Identity(4 * n, 4 * n);
  for (int i = 0; i < n; ++i) f.block(posCol(i), posCol(i) + 2, 2, 2) = kDt * Eigen::Matrix2d::Identity();
  return f;
}

// H_c: one 2-row block z_kl = p_k - p_l for every ordered pair k != l. The reversed pairs are redundant (same
// rows up to sign) but are what the paper stacks; they must not change the rank.
MatrixXd relativePositionMeasurement(int n) {
  MatrixXd h = MatrixXd::Zero(2 * n * (n - 1), 4 * n);
  Index row = 0;
  for (int k = 0; k < n; ++k) {
    for (int l = 0; l < n; ++l) {
      if (k == l) continue;
      h.block(row, posCol(k), 2, 2) = Eigen::Matrix2d::Identity();
      h.block(row, posCol(l), 2, 2) = -Eigen::Matrix2d::Identity();
      row += 2;
    }
  }
  return h;
}

// Appends an absolute (GNSS) position measurement of one UAV.
MatrixXd withGnssFix(const MatrixXd& h, int uav) {
  MatrixXd out = MatrixXd::Zero(h.rows() + 2, h.cols());
  out.topRows(h.rows()) = h;
  out.block(h.rows(), posCol(uav), 2, 2) = Eigen::Matrix2d::Identity();
  return out;
}

// O = [H; H F; H F^2; ...; H F^(N-1)] with N = dim(x): by Cayley–Hamilton higher powers add no new rows.
MatrixXd observabilityMatrix(const MatrixXd& h, const MatrixXd& f) {
  const Index dim = f.rows();
  MatrixXd o(h.rows() * dim, dim);
  MatrixXd hfk = h;
  for (Index k = 0; k < dim; ++k) {
    o.middleRows(k * h.rows(), h.rows()) = hfk;
    hfk = hfk * f;
  }
  return o;
}

struct RankReport {
  Index rank = 0;
  VectorXd sigma;  // singular values, descending
  MatrixXd v;      // right singular vectors, columns in the same order
  double tolerance = 0.0;
};

// Numerical rank from the SVD with the standard LAPACK / numpy threshold sigma_max * max(rows, cols) * eps: the
// singular values that are zero in exact arithmetic come out as rounding noise of about that size. The SVD is used
// rather than an LU because velocity columns enter O only through k * dt <= (4n - 1) * 0.01, while position columns
// carry 1. The SVD exposes how small those genuine velocity directions get next to the rounding noise, and the
// tests below assert that gap, so the rank decision cannot be a threshold accident.
RankReport numericalRank(const MatrixXd& o) {
  Eigen::JacobiSVD<MatrixXd> svd(o, Eigen::ComputeThinV);
  RankReport r;
  r.sigma = svd.singularValues();
  r.v = svd.matrixV();
  r.tolerance = r.sigma(0) * static_cast<double>(std::max(o.rows(), o.cols())) * std::numeric_limits<double>::epsilon();
  while (r.rank < r.sigma.size() && r.sigma(r.rank) > r.tolerance) ++r.rank;
  return r;
}

// The paper's null-space basis 1_n ⊗ e_j, j = 1..4: the same shift of x, y, vx or vy applied to every UAV.
MatrixXd commonModeBasis(int n) {
  MatrixXd basis = MatrixXd::Zero(4 * n, 4);
  for (int i = 0; i < n; ++i) basis.block(posCol(i), 0, 4, 4) = Eigen::Matrix4d::Identity();
  return basis;
}

class SwarmObservability : public ::testing::TestWithParam<int> {};

TEST_P(SwarmObservability, RelativePositionsLeaveExactlyFourUnobservableDirections) {
  // GIVEN n UAVs observed only through all pairwise relative positions
  const int n = GetParam();
  const MatrixXd o = observabilityMatrix(relativePositionMeasurement(n), swarmTransition(n));
  ASSERT_EQ(o.rows(), 2 * n * (n - 1) * 4 * n);
  ASSERT_EQ(o.cols(), 4 * n);

  // WHEN its numerical rank is taken
  const RankReport r = numericalRank(o);

  // THEN it is 4n - 4
  EXPECT_EQ(r.rank, 4 * n - 4);
  // AND the last kept singular value towers over the first dropped one (measured: 0.13 .. 1.2 against
  // 7e-18 .. 2e-14, ratio > 1e13), so any threshold within six decades would give the same answer
  const double kept = r.sigma(4 * n - 5);
  const double dropped = r.sigma(4 * n - 4);
  EXPECT_GT(kept, 1e6 * dropped) << "kept " << kept << " dropped " << dropped;
  EXPECT_GT(kept, 1e3 * r.tolerance);
  EXPECT_LT(r.sigma.tail(4).maxCoeff(), r.tolerance);
}

TEST_P(SwarmObservability, NullSpaceIsCommonTranslationAndCommonVelocity) {
  // GIVEN the relative-only observability matrix and the paper's four common-mode vectors
  const int n = GetParam();
  const MatrixXd o = observabilityMatrix(relativePositionMeasurement(n), swarmTransition(n));
  const MatrixXd basis = commonModeBasis(n);

  // THEN O maps each of them to zero (exactly: every entry is a ±1 or ±k dt pair that cancels)
  for (Index j = 0; j < 4; ++j) {
    EXPECT_LT((o * basis.col(j)).lpNorm<Eigen::Infinity>(), 1e-12) << "j=" << j;
  }
  // AND they are linearly independent (orthogonal with squared norm n), so with rank 4n - 4 they span the null space
  EXPECT_LT((basis.transpose() * basis - n * Eigen::Matrix4d::Identity()).norm(), 1e-15);
  Eigen::FullPivLU<MatrixXd> lu(basis);
  EXPECT_EQ(lu.rank(), 4);
  // AND, as a cross-check, the four right singular vectors the SVD reports as null lie inside their span
  const RankReport r = numericalRank(o);
  const MatrixXd svdNull = r.v.rightCols(4);
  const MatrixXd projector = basis * basis.transpose() / static_cast<double>(n);
  EXPECT_LT((svdNull - projector * svdNull).norm(), 1e-9);
}

TEST_P(SwarmObservability, OneAbsoluteFixMakesTheWholeSwarmObservable) {
  // GIVEN the same swarm plus one GNSS position measurement of UAV 0
  const int n = GetParam();
  const MatrixXd o = observabilityMatrix(withGnssFix(relativePositionMeasurement(n), 0), swarmTransition(n));

  // WHEN the rank is taken
  const RankReport r = numericalRank(o);

  // THEN it is full, 4n: the fix pins p_0, relative positions then pin every p_i; in H F^k the fix row reads
  // p_0 + k dt v_0, so v_0 is seen through how p_0 moves, and relative rows give every v_i - v_0 the same way
  EXPECT_EQ(r.rank, 4 * n);
  // AND the weakest direction (a velocity, scaled by dt) is still far above the noise floor (measured 0.04 .. 0.13
  // against a threshold of ~1e-13)
  EXPECT_GT(r.sigma(4 * n - 1), 1e3 * r.tolerance);
  EXPECT_GT(r.sigma(4 * n - 1), 1e-3);
  // AND the former null directions are now seen only through the fix rows: a common shift of position gives
  // 1 in each of the 4n time blocks, a common velocity gives k dt in block k
  const MatrixXd basis = commonModeBasis(n);
  double velocityResponse2 = 0.0;
  for (int k = 0; k < 4 * n; ++k) velocityResponse2 += (k * kDt) * (k * kDt);
  for (Index j = 0; j < 4; ++j) {
    const double expected = j < 2 ? std::sqrt(4.0 * n) : std::sqrt(velocityResponse2);
    EXPECT_NEAR((o * basis.col(j)).norm(), expected, 1e-12) << "j=" << j;
  }
}

TEST_P(SwarmObservability, FixOnAnyMemberIsEquivalent) {
  // GIVEN the fix on the last UAV instead of UAV 0
  const int n = GetParam();
  const RankReport r =
      numericalRank(observabilityMatrix(withGnssFix(relativePositionMeasurement(n), n - 1), swarmTransition(n)));
  // THEN the rank is still 4n: which member carries GNSS does not matter, only that one does
  EXPECT_EQ(r.rank, 4 * n);
}

INSTANTIATE_TEST_SUITE_P(SwarmSizes, SwarmObservability, ::testing::Range(2, 7),
                         [](const ::testing::TestParamInfo<int>& swarm) { return "n" + std::to_string(swarm.param); });

}  // namespace

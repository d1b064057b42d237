#pragma once
// Fixed-size linear Kalman filter. Stateless operations on a (mean, covariance) pair so one implementation serves
// the bank of neighbour filters and the focal estimator. Corrections use the Joseph form and LDLT solves: the
// focal filter runs 100 corrections a second for hours, and the short form P - KHP drifts from symmetric
// positive definite in that time.

#include <Eigen/Cholesky>
#include <Eigen/Core>

namespace swa::agent {

template <int NX>
struct StateCov {
  using Vec = Eigen::Matrix<double, NX, 1>;
  using Mat = Eigen::Matrix<double, NX, NX>;
  Vec x = Vec::Zero();
  Mat P = Mat::Identity();
};

template <int NZ>
struct Innovation {
  Eigen::Matrix<double, NZ, 1> y;      // z - Hx
  Eigen::Matrix<double, NZ, NZ> S;     // HPH' + R
  double mahalanobis2 = 0.0;           // y' S^-1 y
  bool valid = false;                  // S positive definite
};

template <int NX, int NU = 1>
struct Lkf {
  using Vec = Eigen::Matrix<double, NX, 1>;
  using Mat = Eigen::Matrix<double, NX, NX>;
  using InputMat = Eigen::Matrix<double, NX, NU>;
  using Input = Eigen::Matrix<double, NU, 1>;

  static void predict(StateCov<NX>& s, const Mat& F, const Mat& Q) {
    s.x = F * s.x;
    s.P = F * s.P * F.transpose() + Q;
    symmetrise(s.P);
  }

  static void predict(StateCov<NX>& s, const Mat& F, const InputMat& B, const Input& u, const Mat& Q) {
    s.x = F * s.x + B * u;
    s.P = F * s.P * F.transpose() + Q;
    symmetrise(s.P);
  }

  template <int NZ>
  static Innovation<NZ> innovation(const StateCov<NX>& s, const Eigen::Matrix<double, NZ, NX>& H,
                                   const Eigen::Matrix<double, NZ, 1>& z,
                                   const Eigen::Matrix<double, NZ, NZ>& R) {
    Innovation<NZ> in;
    in.y = z - H * s.x;
    in.S = H * s.P * H.transpose() + R;
    const Eigen::LDLT<Eigen::Matrix<double, NZ, NZ>> ldlt(in.S);
    in.valid = ldlt.info() == Eigen::Success && ldlt.isPositive() && (ldlt.vectorD().array() > 0.0).all();
    in.mahalanobis2 = in.valid ? in.y.dot(ldlt.solve(in.y)) : 0.0;
    return in;
  }

  // Returns false (and leaves the state untouched) when the innovation covariance is not positive definite.
  template <int NZ>
  static bool correct(StateCov<NX>& s, const Eigen::Matrix<double, NZ, NX>& H,
                      const Eigen::Matrix<double, NZ, 1>& z, const Eigen::Matrix<double, NZ, NZ>& R,
                      Innovation<NZ>* out = nullptr) {
    using HMat = Eigen::Matrix<double, NZ, NX>;
    const HMat HP = H * s.P;
    const Eigen::Matrix<double, NZ, NZ> S = HP * H.transpose() + R;
    const Eigen::LDLT<Eigen::Matrix<double, NZ, NZ>> ldlt(S);
    const bool ok = ldlt.info() == Eigen::Success && ldlt.isPositive() && (ldlt.vectorD().array() > 0.0).all();
    const Eigen::Matrix<double, NZ, 1> y = z - H * s.x;
    if (out != nullptr) {
      out->y = y;
      out->S = S;
      out->valid = ok;
      out->mahalanobis2 = ok ? y.dot(ldlt.solve(y)) : 0.0;
    }
    if (!ok) return false;
    // K = P H' S^-1, computed as (S^-1 H P)' because S and P are symmetric.
    const Eigen::Matrix<double, NX, NZ> K = ldlt.solve(HP).transpose();
    s.x += K * y;
    const Mat IKH = Mat::Identity() - K * H;
    s.P = IKH * s.P * IKH.transpose() + K * R * K.transpose();
    symmetrise(s.P);
    return true;
  }

  static void symmetrise(Mat& P) { P = 0.5 * (P + P.transpose()).eval(); }
};

}  // namespace swa::agent

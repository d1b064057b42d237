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
  Eigen::Matrix<double, NZ, 1> y;       // z - Hx
  Eigen::Matrix<double, NZ, NZ> S;      // HPH' + R
  Eigen::Matrix<double, NZ, NZ> S_inv;  // valid only when `valid`
  double mahalanobis2 = 0.0;            // y' S^-1 y
  bool valid = false;                   // S positive definite
};

// Inverse of a symmetric positive-definite matrix; false when it is not positive definite. Measurements here are 1-
// or 2-D, where the closed form is exact and several times cheaper than a factorisation.
template <int N>
bool invertSpd(const Eigen::Matrix<double, N, N>& S, Eigen::Matrix<double, N, N>& S_inv) {
  if constexpr (N == 1) {
    if (!(S(0, 0) > 0.0)) return false;
    S_inv(0, 0) = 1.0 / S(0, 0);
    return true;
  } else if constexpr (N == 2) {
    const double det = S(0, 0) * S(1, 1) - S(0, 1) * S(1, 0);
    if (!(S(0, 0) > 0.0) || !(det > 0.0)) return false;
    S_inv << S(1, 1) / det, -S(0, 1) / det, -S(1, 0) / det, S(0, 0) / det;
    return true;
  } else {
    const Eigen::LDLT<Eigen::Matrix<double, N, N>> ldlt(S);
    if (ldlt.info() != Eigen::Success || !ldlt.isPositive() || !(ldlt.vectorD().array() > 0.0).all()) return false;
    S_inv = ldlt.solve(Eigen::Matrix<double, N, N>::Identity());
    return true;
  }
}

template <int NX, int NU = 1>
struct Lkf {
  using Vec = Eigen::Matrix<double, NX, 1>;
  using Mat = Eigen::Matrix<double, NX, NX>;
  using InputMat = Eigen::Matrix<double, NX, NU>;
  using Input = Eigen::Matrix<double, NU, 1>;

  static void predict(StateCov<NX>& s, const Mat& F, const Mat& Q) {
    s.x = F * s.x;
    propagateCovariance(s.P, F, Q);
  }

  static void predict(StateCov<NX>& s, const Mat& F, const InputMat& B, const Input& u, const Mat& Q) {
    s.x = F * s.x + B * u;
    propagateCovariance(s.P, F, Q);
  }

  template <int NZ>
  static Innovation<NZ> innovation(const StateCov<NX>& s, const Eigen::Matrix<double, NZ, NX>& H,
                                   const Eigen::Matrix<double, NZ, 1>& z, const Eigen::Matrix<double, NZ, NZ>& R) {
    Innovation<NZ> in;
    in.y = z - H * s.x;
    in.S.noalias() = H * s.P * H.transpose();
    in.S += R;
    in.valid = invertSpd<NZ>(in.S, in.S_inv);
    in.mahalanobis2 = in.valid ? in.y.dot(in.S_inv * in.y) : 0.0;
    return in;
  }

  // Applies a correction whose innovation was computed (and possibly gated) by the caller.
  // Joseph form, expanded so it costs O(n^2 m) instead of O(n^3): with A = (I - KH)P,
  // (I - KH) P (I - KH)' + K R K' = A - (A H') K' + K R K'.
  template <int NZ>
  static bool correct(StateCov<NX>& s, const Eigen::Matrix<double, NZ, NX>& H, const Eigen::Matrix<double, NZ, NZ>& R,
                      const Innovation<NZ>& in) {
    if (!in.valid) return false;
    const Eigen::Matrix<double, NZ, NX> HP = H * s.P;
    // K = P H' S^-1 = (S^-1 H P)' because S and P are symmetric.
    const Eigen::Matrix<double, NX, NZ> K = (in.S_inv * HP).transpose();
    s.x.noalias() += K * in.y;
    Mat A = s.P;
    A.noalias() -= K * HP;
    const Eigen::Matrix<double, NX, NZ> AHt = A * H.transpose();
    s.P = A;
    s.P.noalias() -= AHt * K.transpose();
    s.P.noalias() += K * R * K.transpose();
    symmetrise(s.P);
    return true;
  }

  // Returns false (and leaves the state untouched) when the innovation covariance is not positive definite.
  template <int NZ>
  static bool correct(StateCov<NX>& s, const Eigen::Matrix<double, NZ, NX>& H, const Eigen::Matrix<double, NZ, 1>& z,
                      const Eigen::Matrix<double, NZ, NZ>& R, Innovation<NZ>* out = nullptr) {
    const Innovation<NZ> in = innovation<NZ>(s, H, z, R);
    if (out != nullptr) *out = in;
    return correct<NZ>(s, H, R, in);
  }

  static void symmetrise(Mat& P) { P = 0.5 * (P + P.transpose()).eval(); }

 private:
  static void propagateCovariance(Mat& P, const Mat& F, const Mat& Q) {
    Mat FP;
    FP.noalias() = F * P;
    P.noalias() = FP * F.transpose();
    P += Q;
    symmetrise(P);
  }
};

}  // namespace swa::agent

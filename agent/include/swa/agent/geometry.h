#pragma once
// Frame conventions (DESIGN §2): heading psi rotates the body frame B into the stable frame S, counter-clockwise
// positive, so z_S = R(psi) z_B. A neighbour straight ahead of a UAV heading east (psi = 0, world x = east) is east.

#include <cmath>

#include <Eigen/Core>
#include <Eigen/LU>  // determinant()

namespace swa::agent {

using Vec2 = Eigen::Vector2d;
using Mat2 = Eigen::Matrix2d;

inline Mat2 rotation(double psi) {
  const double c = std::cos(psi);
  const double s = std::sin(psi);
  Mat2 R;
  R << c, -s, s, c;
  return R;
}

inline bool isFinite(const Vec2& v) { return std::isfinite(v.x()) && std::isfinite(v.y()); }
inline bool isFinite(const Mat2& m) { return m.allFinite(); }

// Symmetric and positive definite, judged on the 2x2 determinant and trace.
inline bool isCovariance(const Mat2& m) {
  return m.allFinite() && std::abs(m(0, 1) - m(1, 0)) <= 1e-9 * (1.0 + m.cwiseAbs().maxCoeff()) && m(0, 0) > 0.0 &&
         m.determinant() > 0.0;
}

}  // namespace swa::agent

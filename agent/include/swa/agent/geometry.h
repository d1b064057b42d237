#pragma once
// Frame conventions (DESIGN §2): heading psi rotates the body frame B into the stable frame S, counter-clockwise
// positive, so z_S = R(psi) z_B. A neighbour straight ahead of a UAV heading east (psi = 0, world x = east) is east.

#include <cmath>

#include <Eigen/Core>

namespace swa::agent {

using Vec2 = Eigen::Vector2d;
using Mat2 = Eigen::Matrix2d;
using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;

// Standard gravity (BIPM, 3rd CGPM 1901): what an accelerometer at rest reads, up to local variation of < 0.3 %.
constexpr double kStandardGravity_mps2 = 9.80665;

inline Mat2 rotation(double psi) {
  const double c = std::cos(psi);
  const double s = std::sin(psi);
  Mat2 R;
  R << c, -s, s, c;
  return R;
}

// The body's tilt in SWA's convention (DESIGN §3.4): body -> level frame (x along the heading, y left, z up) for a
// body tilted so that its z axis leans by `pitch_rad` towards level +x and by `roll_rad` towards level +y, so that
// small angles (pitch, roll) give the lateral acceleration q_c (pitch, roll) of the paper's tilt model. The z axis
// of the body in the level frame is (sin pitch cos roll, sin roll, cos pitch cos roll).
inline Mat3 tiltRotation(double roll_rad, double pitch_rad) {
  const double cr = std::cos(roll_rad);
  const double sr = std::sin(roll_rad);
  const double cp = std::cos(pitch_rad);
  const double sp = std::sin(pitch_rad);
  Mat3 pitch;  // about level y, +pitch leans z towards +x
  pitch << cp, 0.0, sp, 0.0, 1.0, 0.0, -sp, 0.0, cp;
  Mat3 roll;  // about x by -roll, which leans z towards +y
  roll << 1.0, 0.0, 0.0, 0.0, cr, sr, 0.0, -sr, cr;
  return pitch * roll;
}

inline bool isFinite(const Vec2& v) { return std::isfinite(v.x()) && std::isfinite(v.y()); }
inline bool isFinite(const Mat2& m) { return m.allFinite(); }

// Largest variance a sensor may claim (1e6 m std): beyond it the products in the filters overflow, and such a
// measurement carries no information anyway.
constexpr double kMaxVariance = 1e12;

// Symmetric, positive definite and not absurdly large, judged on the 2x2 determinant.
inline bool isCovariance(const Mat2& m) {
  const double det = m(0, 0) * m(1, 1) - m(0, 1) * m(1, 0);
  return m.allFinite() && std::abs(m(0, 1) - m(1, 0)) <= 1e-9 * (1.0 + m.cwiseAbs().maxCoeff()) && m(0, 0) > 0.0 &&
         m(0, 0) <= kMaxVariance && m(1, 1) <= kMaxVariance && std::isfinite(det) && det > 0.0;
}

// Gabriel's test (DESIGN §3.2): m lies in the closed disc with the segment a-b as diameter, i.e. the angle a-m-b is
// 90 deg or more. A point on the circle counts as inside (so a square loses its diagonals), with a relative tolerance
// that keeps exact lattices exact under rounding.
inline bool inDiametralDisc(const Vec2& a, const Vec2& b, const Vec2& m) {
  constexpr double kOnCircleTolerance = 1e-9;
  return (a - m).dot(b - m) <= kOnCircleTolerance * (b - a).squaredNorm();
}

}  // namespace swa::agent

#pragma once
// Floating-frame estimator (paper §III-B, DESIGN §3.3): the desired position of the focal UAV is the centre of a
// circle of radius r through its neighbours. Positions are relative to the focal UAV in its stable frame, so the
// focal UAV sits at the origin and the result r_c is "where I should be" relative to "where I am".

#include <array>
#include <cstdint>

#include "swa/agent/config.h"
#include "swa/agent/geometry.h"

namespace swa::agent {

constexpr int kMaxNeighbours = 16;

struct NeighbourPositions {
  int count = 0;
  std::array<Vec2, kMaxNeighbours> position{};  // sorted nearest first
};

using NeighbourCovariances = std::array<Mat2, kMaxNeighbours>;  // same order as NeighbourPositions

enum class FitCase : std::uint8_t {
  kNone,              // no neighbours: no frame
  kOne,               // n = 1
  kTwo,               // n = 2, the intersection closer to self
  kTwoFarApart,       // n = 2 farther than 2r apart: midpoint
  kCoincident,        // neighbours on top of each other or of self: a fixed, documented direction is used
  kAlgebraic,         // n >= 3, linear least squares (Kasa)
  kFixedRadius,       // n >= 3, (weighted) least squares on |p_j - c| = r, by Newton
  kCollinearFallback  // n >= 3 collinear / ill-conditioned algebraic system: the n = 2 solution of the two nearest
};

struct FrameFit {
  bool valid = false;
  Vec2 centre = Vec2::Zero();  // r_c: floating-frame origin relative to self
  FitCase fit_case = FitCase::kNone;
  int iterations = 0;  // Newton iterations used
};

// `far_weight` weighs the fixed-radius residuals of every neighbour beyond the two nearest (the two nearest weigh 1);
// the other cases ignore it.
FrameFit fitFloatingFrame(const NeighbourPositions& neighbours, double radius, CircleFit method,
                          double far_weight = 1.0);

// Covariance of `fit.centre` given the neighbours' position covariances (independent of one another), to first
// order in the Gauss-Newton approximation: r_c moves by J_j dp_j when neighbour j moves by dp_j, leaving out the
// residuals' curvature (exact where the neighbours lie on the circle; tests/unit/test_fit_covariance.cpp checks it
// against a Monte Carlo of the fit within 5 %). For the fixed-radius fit (and n = 2, its exact case)
// J_j = A^-1 w_j u_j u_j' with u_j the unit vector centre -> neighbour and A = sum w_j u_j u_j' (the Gauss-Newton
// normal matrix at the optimum): a neighbour's error along the circle's tangent does not move the centre, and a
// centre held by two nearly opposite neighbours is poorly known across them. False for the cases it does not model
// (algebraic fit, coincident points): the caller then keeps its configured noise.
bool fitCovariance(const NeighbourPositions& neighbours, const NeighbourCovariances& covariances, const FrameFit& fit,
                   double radius, double far_weight, Mat2& out);

// The individual cases, exposed for the tests and the benchmark.
FrameFit fitOne(const Vec2& p, double radius);
FrameFit fitTwo(const Vec2& p1, const Vec2& p2, double radius);
FrameFit fitAlgebraic(const NeighbourPositions& neighbours, double radius);
FrameFit fitFixedRadius(const NeighbourPositions& neighbours, double radius, double far_weight = 1.0);

}  // namespace swa::agent

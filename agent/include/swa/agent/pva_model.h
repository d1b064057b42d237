#pragma once
// Discrete 2-D constant-acceleration model shared by the neighbour tracks (F_o, no damping) and the focal
// estimator (F_f, velocity damped by e_d = exp(-dt/tau) towards the commanded velocity).
//
// Table I gives Q per computational step of the reference implementation (100 Hz). Filters here run at whatever
// rate their samples arrive, so Q is scaled linearly with dt: ten 10 ms predictions then add the same noise as one
// 100 ms prediction, and the tuning does not depend on the sensor rates.

#include "swa/agent/geometry.h"
#include "swa/agent/lkf.h"
#include "swa/agent/state_layout.h"

namespace swa::agent {

struct PvaNoise {
  double pos = 0.0;  // m^2 per reference step
  double vel = 0.0;  // m^2/s^2
  double acc = 0.0;  // m^2/s^4
  double ref_dt_s = 0.01;
};

using Pva = Lkf<pva::kDim, 2>;
using PvaState = StateCov<pva::kDim>;
using PvaMat = Pva::Mat;

// damping = e_d in (0, 1]; 1 gives the undamped constant-acceleration model F_o.
inline PvaMat pvaTransition(double dt, double damping = 1.0) {
  PvaMat F = PvaMat::Identity();
  const Mat2 I = Mat2::Identity();
  block<pva::Pos, pva::Vel>(F) = I * dt;
  block<pva::Pos, pva::Acc>(F) = I * (0.5 * dt * dt);
  block<pva::Vel, pva::Vel>(F) = I * damping;
  block<pva::Vel, pva::Acc>(F) = I * dt;
  return F;
}

inline PvaMat pvaProcessNoise(const PvaNoise& q, double dt) {
  const double scale = dt / q.ref_dt_s;
  PvaMat Q = PvaMat::Zero();
  const Mat2 I = Mat2::Identity();
  block<pva::Pos, pva::Pos>(Q) = I * (q.pos * scale);
  block<pva::Vel, pva::Vel>(Q) = I * (q.vel * scale);
  block<pva::Acc, pva::Acc>(Q) = I * (q.acc * scale);
  return Q;
}

inline Eigen::Matrix<double, 2, pva::kDim> positionObservation() {
  Eigen::Matrix<double, 2, pva::kDim> H = Eigen::Matrix<double, 2, pva::kDim>::Zero();
  block<Slice<0, 2>, pva::Pos>(H) = Mat2::Identity();
  return H;
}

inline Eigen::Matrix<double, 2, pva::kDim> accelerationObservation() {
  Eigen::Matrix<double, 2, pva::kDim> H = Eigen::Matrix<double, 2, pva::kDim>::Zero();
  block<Slice<0, 2>, pva::Acc>(H) = Mat2::Identity();
  return H;
}

}  // namespace swa::agent

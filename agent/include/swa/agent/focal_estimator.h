#pragma once
// Focal state estimator (paper §III-C): the UAV's own position, velocity and acceleration in a frame that is not
// fixed to the ground (the floating frame in `swa` mode, the take-off frame in `standalone`). Velocity is damped
// towards the commanded velocity (e_d = exp(-dt/tau)); position and tilt-derived acceleration arrive
// unsynchronised and are applied as they come.

#include "swa/agent/config.h"
#include "swa/agent/pva_model.h"
#include "swa/agent/samples.h"

namespace swa::agent {

class FocalEstimator {
 public:
  explicit FocalEstimator(const FocalConfig& config);

  bool initialized() const { return initialized_; }
  void reset() { initialized_ = false; }
  // Starts the filter at a measured position with the measurement's covariance; velocity and acceleration start at
  // zero with broad priors (the UAV may already be moving).
  void initialize(StampNs stamp, const Vec2& position, const Mat2& position_cov);

  // Prediction to `stamp` with the velocity command u in force since the last prediction. Earlier stamps are a
  // no-op: a measurement that arrives late is applied at the filter's time.
  void predictTo(StampNs stamp, const Vec2& u);
  bool correctPosition(const Vec2& z, const Mat2& R);
  bool correctAcceleration(const Vec2& z, const Mat2& R);

  // The frame origin moved by `delta` (new origin - old origin): the UAV did not, so its coordinates shift by
  // -delta while velocity and acceleration (frame-parallel) are unchanged.
  void shiftFrame(const Vec2& delta);
  // The frame's velocity changed by `delta` (a mission's next leg, mission.h): the UAV's did not, so its velocity in
  // the frame shifts by -delta.
  void shiftVelocity(const Vec2& delta);
  // The old frame cannot be related to the new one: restart position from the measurement, keep velocity and
  // acceleration, and drop the position cross-covariances that referred to the old frame.
  void resetPosition(const Vec2& z, const Mat2& R);

  StampNs time() const { return time_ns_; }
  Vec2 position() const { return segment<pva::Pos>(state_.x); }
  Vec2 velocity() const { return segment<pva::Vel>(state_.x); }
  Vec2 acceleration() const { return segment<pva::Acc>(state_.x); }
  Mat2 positionCov() const { return block<pva::Pos, pva::Pos>(state_.P); }
  Mat2 velocityCov() const { return block<pva::Vel, pva::Vel>(state_.P); }
  const PvaState& state() const { return state_; }

 private:
  void cacheModel(double dt);

  FocalConfig config_;
  PvaNoise noise_;
  PvaState state_;
  StampNs time_ns_ = 0;
  bool initialized_ = false;
  // The IMU arrives at a fixed rate, so F, B and Q are rebuilt only when dt changes (exp() is not free).
  double cached_dt_ = -1.0;
  PvaMat F_, Q_;
  Eigen::Matrix<double, pva::kDim, 2> B_;
};

}  // namespace swa::agent

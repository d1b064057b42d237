#include "swa/agent/focal_estimator.h"

#include <cmath>

namespace swa::agent {
namespace {

// Priors at initialisation: a UAV that loses GNSS may be moving at cruise speed; tilt tells acceleration within R_a.
constexpr double kInitVelVar = 1.0;   // m^2/s^2
constexpr double kInitAccVar = 2.25;  // m^2/s^4
constexpr double kMaxPredictionS = 10.0;

}  // namespace

FocalEstimator::FocalEstimator(const FocalConfig& config)
    : config_(config),
      noise_{config.q_pos_m2 * config.q_scale, config.q_vel_m2ps2 * config.q_scale, config.q_acc_m2ps4 * config.q_scale,
             config.q_ref_dt_s} {}

void FocalEstimator::initialize(StampNs stamp, const Vec2& position, const Mat2& position_cov) {
  state_.x.setZero();
  segment<pva::Pos>(state_.x) = position;
  state_.P.setZero();
  block<pva::Pos, pva::Pos>(state_.P) = position_cov;
  block<pva::Vel, pva::Vel>(state_.P) = Mat2::Identity() * kInitVelVar;
  block<pva::Acc, pva::Acc>(state_.P) = Mat2::Identity() * kInitAccVar;
  time_ns_ = stamp;
  initialized_ = true;
}

void FocalEstimator::cacheModel(double dt) {
  if (dt == cached_dt_) return;
  const double e_d = std::exp(-dt / config_.tau_s);
  F_ = pvaTransition(dt, e_d);
  Q_ = pvaProcessNoise(noise_, dt);
  B_.setZero();
  B_.template block<2, 2>(pva::Vel::offset, 0) = Mat2::Identity() * (1.0 - e_d);
  cached_dt_ = dt;
}

void FocalEstimator::predictTo(StampNs stamp, const Vec2& u) {
  if (!initialized_ || stamp <= time_ns_) return;
  const double dt = secondsBetween(time_ns_, stamp);
  if (dt > kMaxPredictionS) {
    // After a sensor gap this long the estimate means nothing (and the covariance would overflow): start over
    // from the next reference measurement.
    initialized_ = false;
    return;
  }
  cacheModel(dt);
  Pva::predict(state_, F_, B_, u, Q_);
  time_ns_ = stamp;
}

bool FocalEstimator::correctPosition(const Vec2& z, const Mat2& R) {
  return initialized_ && Pva::correct<2>(state_, positionObservation(), z, R);
}

bool FocalEstimator::correctAcceleration(const Vec2& z, const Mat2& R) {
  return initialized_ && Pva::correct<2>(state_, accelerationObservation(), z, R);
}

void FocalEstimator::shiftFrame(const Vec2& delta) { segment<pva::Pos>(state_.x) -= delta; }

void FocalEstimator::shiftVelocity(const Vec2& delta) { segment<pva::Vel>(state_.x) -= delta; }

void FocalEstimator::resetPosition(const Vec2& z, const Mat2& R) {
  segment<pva::Pos>(state_.x) = z;
  block<pva::Pos, pva::Pos>(state_.P) = R;
  block<pva::Pos, pva::Vel>(state_.P).setZero();
  block<pva::Pos, pva::Acc>(state_.P).setZero();
  block<pva::Vel, pva::Pos>(state_.P).setZero();
  block<pva::Acc, pva::Pos>(state_.P).setZero();
}

}  // namespace swa::agent

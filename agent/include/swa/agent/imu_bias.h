#pragma once
// IMU-bias removal (DESIGN §3.4): the running mean of the tilt-derived acceleration is taken as the accelerometer's
// bias and subtracted before the focal filter's acceleration correction,
//   b <- b + (a - b) dt / min(T_b, max(1 s, t)),   t = time averaged since the last reset.
// It rests on one prior: a hovering UAV's true acceleration averages to zero over T_b (its velocity stays bounded),
// so the mean of what the IMU reports is its bias. That prior is false while the UAV manoeuvres, so the mean is
// frozen (still subtracted, no longer updated) while the command in force is faster than `freeze_speed_mps` and for
// `freeze_hold_s` after: a manoeuvre's slow phases (turning round, braking) carry its largest accelerations. On a
// mission the command is taken relative to the plan (a steady cruise accelerates no more than a hover), and each
// change of the plan's velocity is a manoeuvre.
// Works in the body frame, where the bias of a tilt sensor is constant even if the heading turns.
//
// Why not a bias state in the filter: an 8-state filter did nothing with the paper's Q_f and made drift worse with a
// 100x smaller Q_f (DESIGN §3.4) — relative position measurements cannot tell a bias from a real acceleration.

#include "swa/agent/geometry.h"
#include "swa/agent/samples.h"

namespace swa::agent {

class ImuBiasRemover {
 public:
  // window_s = 0 turns the remover off: correct() returns its input.
  ImuBiasRemover(double window_s, double freeze_speed_mps, double freeze_hold_s);

  bool enabled() const { return window_s_ > 0.0; }
  // Forgets the mean: the next sample starts a new average (the focal filter restarted).
  void reset();
  // Updates the mean with body-frame acceleration `a` at `stamp` (unless `command_mps` is faster than the freeze
  // speed) and returns a - mean. Stamps must increase; an older or repeated stamp only subtracts.
  Vec2 correct(const Vec2& a, StampNs stamp, const Vec2& command_mps);
  // A manoeuvre that the command does not show began at `stamp` (a mission's next leg: the command relative to the
  // plan stays slow while the UAV accelerates with its swarm): frozen as after a fast command.
  void manoeuvreAt(StampNs stamp) {
    seen_fast_ = true;
    last_fast_ns_ = stamp;
  }

  Vec2 bias() const { return bias_; }
  double averagedSeconds() const { return averaged_s_; }
  bool frozen() const { return frozen_; }

 private:
  double window_s_;
  double freeze_speed_mps_;
  double freeze_hold_s_;
  StampNs last_fast_ns_ = 0;
  bool seen_fast_ = false;
  Vec2 bias_ = Vec2::Zero();
  double averaged_s_ = 0.0;  // t: time over which the mean has been updated since the reset
  StampNs last_ns_ = 0;
  bool started_ = false;
  bool frozen_ = false;
};

}  // namespace swa::agent

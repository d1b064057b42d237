#include "swa/agent/agent.h"

#include <algorithm>
#include <cmath>

#include "swa/agent/controller.h"

namespace swa::agent {
namespace {

// An anchored UAV adds its absolute hold only while its GNSS is fresh; 1 s is ten missed 10 Hz fixes.
constexpr double kGnssFreshS = 1.0;

StampNs toNs(double seconds) { return static_cast<StampNs>(std::llround(seconds * 1e9)); }

}  // namespace

Agent::Agent(const AgentConfig& config)
    : config_(config),
      bank_(config.surroundings),
      focal_(config.focal),
      absolute_(config.focal),
      imu_bias_(config.focal.bias_window_s, config.focal.bias_freeze_speed_mps, config.focal.bias_freeze_hold_s),
      r_acc_(Mat2::Identity() * config.focal.r_acc_m2ps4),
      r_pos_(Mat2::Identity() * config.focal.r_pos_m2),
      imu_clock_(toNs(config.limits.max_stamp_jump_s), config.limits.resync_samples),
      det_clock_(toNs(config.limits.max_stamp_jump_s), config.limits.resync_samples),
      gnss_clock_(toNs(config.limits.max_stamp_jump_s), config.limits.resync_samples) {
  diag_.mode = config.mode;
  stable_.reserve(config.limits.max_detections);
  // A plan that cannot be flown is refused where the configuration is read (config_io); one that reaches the agent
  // anyway is not flown: the agent holds, as without a mission.
  if (!missionProblem(config.mission)) plan_ = MissionPlan(config.mission.legs);
}

bool Agent::acceptStamp(StreamClock& clock, StampNs stamp) {
  // Detections and GNSS are applied on the IMU's timeline (the filters predict to their stamps): a stream whose
  // clock disagrees with it by more than the window would throw the estimates into another time.
  const bool on_imu_timeline = &clock != &imu_clock_ && imu_clock_.started();
  const StampNs window = toNs(config_.limits.max_stamp_jump_s);
  StampNs offset = 0;
  const bool offset_known = on_imu_timeline && !__builtin_sub_overflow(stamp, imu_clock_.last(), &offset);
  switch (clock.check(stamp)) {
    case StreamClock::Verdict::kAccept:
      break;
    case StreamClock::Verdict::kResync:
      ++diag_.stamp_resyncs;
      if (&clock == &imu_clock_) restartTimeline();
      break;
    case StreamClock::Verdict::kOutOfOrder:
      ++diag_.rejected.out_of_order;
      return false;
    case StreamClock::Verdict::kFuture:
      // Far ahead of the stream's own last stamp, but not of the IMU's: the stream was silent (ArduPilot sends no
      // GNSS while its receiver is unhealthy, a detector may send nothing) and is back. Before, its first
      // resync_samples - 1 samples were rejected as future ones, and a regained GNSS was used 0.3 s late.
      if (offset_known && offset <= window && offset >= -window) {
        clock.resume(stamp);
        break;
      }
      ++diag_.rejected.future;
      return false;
  }
  if (!on_imu_timeline) return true;
  if (!offset_known || offset > window) {
    ++diag_.rejected.future;
    return false;
  }
  if (offset < -window) {
    ++diag_.rejected.out_of_order;
    return false;
  }
  return true;
}

void Agent::restartTimeline() {
  // The IMU clock restarted (a producer reboot): every estimate refers to times of the old timeline. Start over as
  // a new agent would, keeping the configuration, the take-off point and the counters.
  bank_ = TrackBank(config_.surroundings);
  focal_.reset();
  absolute_.reset();
  imu_bias_.reset();
  neighbours_ = Neighbourhood{};
  frame_valid_ = false;
  fit_case_ = FitCase::kNone;
  det_clock_ = StreamClock(toNs(config_.limits.max_stamp_jump_s), config_.limits.resync_samples);
  gnss_clock_ = StreamClock(toNs(config_.limits.max_stamp_jump_s), config_.limits.resync_samples);
  gnss_valid_ = false;
  anchor_on_ = false;  // the hold's first fix after the restart is a return: blended in
  // The plan's time is the IMU's: on a new timeline the mission's start means nothing. Holding is the safe end.
  if (mission_start_ns_ && !diag_.mission_aborted) {
    diag_.mission_aborted = true;
    plan_ = MissionPlan();
  }
  mission_start_ns_.reset();
  plan_velocity_.setZero();
  expected_velocity_.setZero();
}

VelocityCommand Agent::onImu(const ImuSample& imu) {
  const bool finite = std::isfinite(imu.roll_rad) && std::isfinite(imu.pitch_rad) && std::isfinite(imu.heading_rad);
  const LimitsConfig& lim = config_.limits;
  const bool use_accelerometer = config_.focal.imu_source == ImuSource::kAccelerometer;
  const AccelerometerSample* acc = imu.accelerometer ? &*imu.accelerometer : nullptr;
  const bool reads_tilt = !use_accelerometer || acc == nullptr;
  const bool acc_finite = acc == nullptr || (acc->specific_force_body_mps2.allFinite() &&
                                             std::isfinite(acc->roll_rad) && std::isfinite(acc->pitch_rad));
  bool accepted = false;
  if (!finite || !acc_finite) {
    ++diag_.rejected.nonfinite;
  } else if (std::abs(imu.heading_rad) > lim.max_abs_heading_rad ||
             (reads_tilt &&
              (std::abs(imu.roll_rad) > lim.max_tilt_rad || std::abs(imu.pitch_rad) > lim.max_tilt_rad))) {
    // The tilt is judged only where it is read: an agent fusing the accelerometer takes its attitude from there (a
    // mission's 7 m/s turn-round takes the tilt model's q_c-scaled angles past the limit while the attitude is 0.6
    // rad).
    ++diag_.rejected.implausible;
  } else if (use_accelerometer && acc != nullptr &&
             (std::abs(acc->roll_rad) > lim.max_tilt_rad || std::abs(acc->pitch_rad) > lim.max_tilt_rad ||
              acc->specific_force_body_mps2.norm() > kMaxSpecificForce_mps2)) {
    ++diag_.rejected.implausible;
  } else {
    accepted = acceptStamp(imu_clock_, imu.stamp_ns);
  }

  // A rejected sample changes nothing: it is answered with the previous command, marked not fresh (the node does
  // not publish it). Whether the UAV should hover because no valid sample arrives is a question of time, which
  // only the caller's clock can answer: a count of rejections would let a flood of bad samples ground the UAV.
  if (accepted) {
    heading_rad_ = imu.heading_rad;
    have_heading_ = true;
    // DESIGN §3.4: pitch gives body-x and roll body-y acceleration, rotated into the stable frame by heading; or
    // the accelerometer's specific force, turned level by its attitude (issue #44).
    // A sample without the accelerometer is read from the tilt and counted (Diagnostics::tilt_fallbacks), not
    // refused: refused, it would go unanswered, and a vehicle whose accelerometer stream starts a moment after its
    // attitude (discovery order; PX4's two topics) would lose control for it.
    if (use_accelerometer && acc == nullptr) ++diag_.tilt_fallbacks;
    const Vec2 acc_body = use_accelerometer && acc != nullptr
                              ? levelAcceleration(*acc)
                              : Vec2(config_.focal.q_c_mps2 * Vec2(imu.pitch_rad, imu.roll_rad));
    const Mat2 to_stable = rotation(imu.heading_rad);
    const Vec2 unbiased_body = imu_bias_.correct(acc_body, imu.stamp_ns, relativeCommand());
    focal_.predictTo(imu.stamp_ns, relativeCommand());
    absolute_.predictTo(imu.stamp_ns, command_);
    takeCommand(imu.stamp_ns);
    advanceMission(imu.stamp_ns);
    focal_.correctAcceleration(to_stable * unbiased_body, r_acc_);
    absolute_.correctAcceleration(to_stable * acc_body, r_acc_);
    command_ = computeCommand(imu.stamp_ns);
    // With a limited field of view every UAV faces the same way: the plan's direction while it moves (all turn
    // alike, from the same plan), else the configured one.
    const double facing_deg = plan_velocity_ == Vec2::Zero()
                                  ? config_.control.facing_deg
                                  : std::atan2(plan_velocity_.y(), plan_velocity_.x()) * 180.0 / M_PI;
    yaw_rate_ = headingRate(imu.heading_rad, config_.sensor, config_.control, facing_deg);
  }

  VelocityCommand cmd;
  cmd.stamp_ns = imu.stamp_ns;
  cmd.answered_stamp_ns = imu.stamp_ns;
  cmd.seq = ++seq_;
  cmd.velocity_mps = command_;
  cmd.yaw_rate_radps = yaw_rate_;
  cmd.fresh = accepted;
  ++diag_.commands;
  refreshDiagnostics(accepted ? imu.stamp_ns : diag_.stamp_ns);
  return cmd;
}

void Agent::convertDetections(const DetectionSet& in) {
  stable_.clear();
  const Mat2 R = rotation(heading_rad_);
  const Mat2 default_cov = Mat2::Identity() * config_.surroundings.r_det_m2;
  const double max_pos = config_.limits.max_abs_position_m;
  for (const Detection& d : in.detections) {
    const bool cov_finite = !d.covariance_m2 || d.covariance_m2->allFinite();
    if (!isFinite(d.position_body_m) || !cov_finite) {
      ++diag_.rejected.nonfinite;
      continue;
    }
    if (d.target_id != kAnonymousId && (d.target_id < 0 || d.target_id > config_.limits.max_target_id)) {
      ++diag_.rejected.bad_id;
      continue;
    }
    if (d.position_body_m.norm() > max_pos || (d.covariance_m2 && !isCovariance(*d.covariance_m2))) {
      ++diag_.rejected.implausible;
      continue;
    }
    StableDetection s;
    s.target_id = d.target_id;
    s.position_m = R * d.position_body_m;
    s.covariance_m2 = d.covariance_m2 ? Mat2(R * *d.covariance_m2 * R.transpose()) : default_cov;
    stable_.push_back(s);
  }
}

void Agent::onDetections(const DetectionSet& in) {
  if (in.detections.size() > config_.limits.max_detections) {
    ++diag_.rejected.oversize;
    return;
  }
  if (!have_heading_) {
    ++diag_.rejected.no_heading;
    return;
  }
  if (!acceptStamp(det_clock_, in.stamp_ns)) return;
  convertDetections(in);
  bank_.update(in.stamp_ns, stable_);
  if (config_.mode != Mode::kStandalone) updateFrame(in.stamp_ns);
  refreshDiagnostics(std::max(diag_.stamp_ns, in.stamp_ns));
}

void Agent::onGnss(const GnssSample& g) {
  if (g.valid) {
    if (!isFinite(g.position_m) || !std::isfinite(g.std_m)) {
      ++diag_.rejected.nonfinite;
      return;
    }
    if (g.std_m <= 0.0 || g.std_m * g.std_m > kMaxVariance || g.position_m.norm() > config_.limits.max_abs_position_m) {
      ++diag_.rejected.implausible;
      return;
    }
  }
  if (!acceptStamp(gnss_clock_, g.stamp_ns)) return;
  gnss_valid_ = g.valid;
  diag_.gnss_valid = g.valid;
  if (!g.valid) {
    if (config_.mission.start == MissionStart::kGnssLoss && !mission_start_ns_) startMission(g.stamp_ns);
    return;
  }
  last_valid_gnss_ns_ = g.stamp_ns;
  if (config_.mode == Mode::kSwa) return;  // the paper's agent never uses GNSS

  const double sigma = std::max(g.std_m, config_.anchor.gnss_min_std_m);
  const Mat2 R = Mat2::Identity() * (sigma * sigma);
  if (!hold_point_set_) {
    hold_point_ = g.position_m;
    hold_point_set_ = true;
  }
  if (!absolute_.initialized()) {  // the first fix, or the first after a restart of the timeline or a long gap
    absolute_.initialize(g.stamp_ns, g.position_m - hold_point_, R);
    return;
  }
  absolute_.predictTo(g.stamp_ns, command_);
  absolute_.correctPosition(g.position_m - hold_point_, R);
}

void Agent::startMission(StampNs stamp) {
  if (plan_.empty() || mission_start_ns_) return;
  mission_start_ns_ = stamp;
  mission_origin_ = absolute_.initialized() ? absolute_.position() : Vec2::Zero();
}

bool Agent::commandMission(const MissionCommand& command) {
  if (missionCommandProblem(command, config_.mission.max_speed_mps, config_.limits.max_abs_position_m)) {
    ++diag_.mission_commands_refused;
    return false;
  }
  pending_command_ = command;
  return true;
}

void Agent::takeCommand(StampNs stamp) {
  if (!pending_command_) return;
  std::vector<MissionLeg> legs;
  if (mission_start_ns_) {
    // The agent never looks back along its plan: what was flown is kept as one straight leg to the point it reached,
    // so that the plan stays one leg longer than the command however many commands come.
    const double at_s = missionTime(stamp);
    if (at_s > 0.0) legs.push_back({plan_.pathAt(at_s) / at_s, at_s});
  } else {
    mission_start_ns_ = stamp;
    mission_origin_ = absolute_.initialized() ? absolute_.position() : Vec2::Zero();
  }
  appendCommand(legs, *pending_command_);
  pending_command_.reset();
  plan_ = MissionPlan(std::move(legs));
  ++diag_.mission_commands;
  diag_.mission_command_stamp_ns = stamp;
}

double Agent::missionTime(StampNs stamp) const {
  return mission_start_ns_ ? secondsBetween(*mission_start_ns_, stamp) : -1.0;
}

void Agent::advanceMission(StampNs stamp) {
  if (config_.mission.start == MissionStart::kTime && !mission_start_ns_ && !diag_.mission_aborted) {
    const StampNs start = toNs(config_.mission.start_s);
    if (stamp >= start) startMission(start);
  }
  const Vec2 next = plan_.velocityAt(missionTime(stamp));
  if (next != plan_velocity_) {
    // The frame changes velocity at once, the UAV does not: its velocity in the frame jumps by the opposite.
    focal_.shiftVelocity(next - plan_velocity_);
    imu_bias_.manoeuvreAt(stamp);
    plan_velocity_ = next;
  }
  // What the swarm is expected to fly: the plan through the vehicle's first-order response (exact for a velocity
  // constant over the step). The formation law damps the velocity against it, not against the plan: the lag of a
  // new leg is the whole swarm's, and the vehicle catches it up by itself.
  if (expected_velocity_ != plan_velocity_ && stamp > expected_at_ns_) {
    const double dt = secondsBetween(expected_at_ns_, stamp);
    const double keep = config_.mission.response_s > 0.0 ? std::exp(-dt / config_.mission.response_s) : 0.0;
    const Vec2 moved = plan_velocity_ + keep * (expected_velocity_ - plan_velocity_);
    // Within a micrometre per second of the plan it is the plan: a hold is then exactly a hold.
    expected_velocity_ = (moved - plan_velocity_).norm() < 1e-6 ? plan_velocity_ : moved;
  }
  expected_at_ns_ = stamp;
}

// Standalone and anchored: the absolute filter's pull towards the take-off point, or during a mission towards the
// plan's path from where the UAV was at its start, damped against the plan's velocity.
Vec2 Agent::absoluteHold(StampNs stamp, const ControlConfig& cc) const {
  const Vec2 target = mission_origin_ + plan_.pathAt(missionTime(stamp));
  return formationVelocity(absolute_.position() - target, absolute_.velocity() - expected_velocity_, cc);
}

Vec2 Agent::computeCommand(StampNs stamp) {
  const ControlConfig& cc = config_.control;
  Vec2 v = Vec2::Zero();
  const bool frame_fresh =
      focal_.initialized() && secondsBetween(last_frame_ns_, stamp) <= config_.focal.frame_timeout_s;
  switch (config_.mode) {
    case Mode::kSwa:
      if (frame_fresh) v = formationVelocity(focal_.position(), relativeVelocity(), cc);
      break;
    case Mode::kStandalone:
      // The baseline keeps holding its take-off point (or following the plan) on dead reckoning after GNSS is gone
      // (and drifts).
      if (absolute_.initialized()) v = absoluteHold(stamp, cc);
      break;
    case Mode::kAnchored: {
      if (frame_fresh) v = formationVelocity(focal_.position(), relativeVelocity(), cc);
      const bool gnss_fresh = gnss_valid_ && secondsBetween(last_valid_gnss_ns_, stamp) <= kGnssFreshS;
      const bool anchor_on = gnss_fresh && absolute_.initialized();
      if (anchor_on && !anchor_on_ && anchor_ever_on_) anchor_ramp_from_ns_ = stamp;
      anchor_on_ = anchor_on;
      anchor_ever_on_ = anchor_ever_on_ || anchor_on;
      if (anchor_on) {
        double weight = 1.0;
        if (anchor_ramp_from_ns_ && config_.anchor.regain_ramp_s > 0.0) {
          weight = std::min(1.0, secondsBetween(*anchor_ramp_from_ns_, stamp) / config_.anchor.regain_ramp_s);
        }
        v += weight * config_.anchor.gain * absoluteHold(stamp, cc);
      }
      break;
    }
  }
  // The formation's correction is saturated, the plan's velocity is not (missionProblem bounds it): a lost agent
  // flies the plan, where its swarm is going.
  const Vec2 correction = saturate(v, cc.v_max_mps);
  return plan_velocity_ == Vec2::Zero() ? correction : Vec2(plan_velocity_ + correction);
}

void Agent::refreshDiagnostics(StampNs stamp) {
  diag_.stamp_ns = stamp;
  const bool standalone = config_.mode == Mode::kStandalone;
  const FocalEstimator& f = standalone ? absolute_ : focal_;
  if (!f.initialized()) {
    diag_.stage = Stage::kInitializing;
  } else if (!standalone && secondsBetween(last_frame_ns_, stamp) > config_.focal.frame_timeout_s) {
    diag_.stage = Stage::kLost;
  } else {
    diag_.stage = Stage::kTracking;
  }
  diag_.position_m = f.position();
  diag_.velocity_mps = f.velocity();
  diag_.position_cov_m2 = f.positionCov();
  diag_.velocity_cov_m2ps2 = f.velocityCov();
  diag_.frame_valid = frame_valid_;
  diag_.frame_centre_m = frame_centre_;
  diag_.fit_case = fit_case_;
  diag_.neighbour_count = neighbours_.count();
  diag_.neighbour_ids = neighbours_.ids;
  diag_.confirmed_tracks = bank_.confirmedCount();
  diag_.tentative_tracks = bank_.tentativeCount();
  diag_.gnss_valid = gnss_valid_;
  diag_.mission_leg = plan_.legAt(missionTime(stamp));
  diag_.plan_velocity_mps = plan_velocity_;
}

}  // namespace swa::agent

#include "swa/sim/world.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

#include "swa/sim/lattice.h"
#include "swa/sim/random.h"
#include "swa/sim/timing.h"

namespace swa::sim {

namespace {

constexpr agent::StampNs kNever = std::numeric_limits<agent::StampNs>::max();

const Scenario& checked(const Scenario& scenario) {
  const double rate = scenario.dynamics.rate_hz;
  if (!(rate > 0.0) || !std::isfinite(rate) || stepPeriodNs(rate) < 1) {
    throw std::invalid_argument("World: dynamics.rate_hz must be positive, finite and at most 1 GHz");
  }
  if (scenario.uav_count < 0) throw std::invalid_argument("World: uav_count must not be negative");
  return scenario;
}

std::uint32_t owner(int id) { return static_cast<std::uint32_t>(id); }

}  // namespace

World::Uav::Uav(const KinematicState& initial, double heading_rad, double turn_rate, OuProcess2 own_gust,
                ImuModel imu_model, MpsModel mps_model, GnssModel gnss_model, Rng latency_stream)
    : state(initial),
      initial_heading_rad(heading_rad),
      turn_rate_radps(turn_rate),
      gust(std::move(own_gust)),
      imu(std::move(imu_model)),
      mps(std::move(mps_model)),
      gnss(std::move(gnss_model)),
      latency_rng(latency_stream) {}

World::Uav World::makeUav(const Scenario& scenario, int id, const agent::Vec2& slot_m, double dt_s) {
  const std::uint64_t seed = scenario.seed;
  const std::uint32_t me = owner(id);

  // Uniform in a disc (radius ~ sqrt(u)): every UAV starts within position_jitter_m of its slot.
  Rng placement(seed, me, Stream::kPlacement);
  const double radius = scenario.formation.position_jitter_m * std::sqrt(placement.uniform());
  const double angle = placement.uniform(-M_PI, M_PI);
  KinematicState initial;
  initial.position_m = slot_m + radius * agent::Vec2(std::cos(angle), std::sin(angle));

  // Both numbers are drawn in either heading mode so the turn rate does not depend on the mode.
  Rng heading(seed, me, Stream::kHeading);
  const double random_heading = heading.uniform(-M_PI, M_PI);
  const double turn_rate = scenario.dynamics.heading_rate_std_radps * heading.normal();
  const double heading0 = scenario.dynamics.heading == HeadingMode::kRandom ? wrapAngle(random_heading) : 0.0;

  return Uav(initial, heading0, turn_rate,
             OuProcess2(scenario.wind.gust_std, scenario.wind.gust_corr_s, dt_s, Rng(seed, me, Stream::kGust)),
             ImuModel(scenario.imu, scenario.agent.focal.q_c_mps2, ImuModel::Streams::of(seed, me)),
             MpsModel(scenario.mps, MpsStreams{Rng(seed, me, Stream::kMpsMiss), Rng(seed, me, Stream::kMpsNoise),
                                               Rng(seed, me, Stream::kMpsClutter), Rng(seed, me, Stream::kMpsOrder)}),
             GnssModel(scenario.gnss, id, Rng(seed, me, Stream::kGnssNoise)), Rng(seed, me, Stream::kMpsLatency));
}

World::World(const Scenario& scenario)
    : scenario_(checked(scenario)),
      dt_ns_(stepPeriodNs(scenario.dynamics.rate_hz)),
      dt_s_(static_cast<double>(dt_ns_) * 1e-9),
      duration_ns_(durationNs(scenario.duration_s)),
      failsafe_timeout_ns_(durationNs(scenario.dynamics.failsafe_timeout_s)),
      mps_latency_ns_(scenario.mps.latency_s > 0.0 ? durationNs(scenario.mps.latency_s) : 0),
      mps_latency_jitter_s_(scenario.mps.latency_jitter_s),
      imu_period_steps_(sensorPeriodSteps(scenario.imu.rate_hz, scenario.dynamics.rate_hz)),
      mps_period_steps_(sensorPeriodSteps(scenario.mps.rate_hz, scenario.dynamics.rate_hz)),
      gnss_period_steps_(sensorPeriodSteps(scenario.gnss.rate_hz, scenario.dynamics.rate_hz)),
      common_gust_(scenario.wind.common_std, scenario.wind.common_corr_s, dt_s_,
                   Rng(scenario.seed, kWorldOwner, Stream::kGust)),
      yaw_response_(-std::expm1(-dt_s_ / scenario.dynamics.yaw_lag_s)),
      collisions_(scenario.uav_count) {
  const auto n = static_cast<std::size_t>(scenario_.uav_count);
  const std::vector<agent::Vec2> slots = hexLattice(scenario_.uav_count, scenario_.formation.spacing_m);
  uavs_.reserve(n);
  for (std::size_t i = 0; i < n; ++i) uavs_.push_back(makeUav(scenario_, static_cast<int>(i), slots[i], dt_s_));
  // At rest in the wind from the start: the thrust already holds against its drag.
  for (Uav& u : uavs_) u.thrust_mps2 = scenario_.dynamics.drag_per_s * (u.state.velocity_mps - meanWind(0));
  truth_.resize(n);
  for (std::size_t i = 0; i < n; ++i) truth_[i].id = static_cast<int>(i);
  positions_.resize(n);
  sensors_.resize(n);
  refreshTruth();
  updateGnssAvailability();
  detectCollisions();
  generateSensors();
}

void World::command(int uav, const agent::VelocityCommand& cmd) {
  if (uav < 0 || uav >= uav_count()) {
    throw std::out_of_range("World::command: no UAV " + std::to_string(uav));
  }
  if (!agent::isFinite(cmd.velocity_mps) || !std::isfinite(cmd.yaw_rate_radps)) return;
  Uav& u = uavs_[static_cast<std::size_t>(uav)];
  u.setpoint_mps = cmd.velocity_mps;
  const double max_yaw = scenario_.dynamics.max_yaw_rate_radps;
  u.yaw_rate_setpoint_radps = std::clamp(cmd.yaw_rate_radps, -max_yaw, max_yaw);
  u.setpoint_arrival_ns = time_ns_;
}

void World::updateFailsafe(Uav& uav, int id) {
  const agent::StampNs age_ns = time_ns_ - uav.setpoint_arrival_ns;
  const bool stale = failsafe_timeout_ns_ != kNever && age_ns > failsafe_timeout_ns_;
  if (stale == uav.failsafe) return;
  uav.failsafe = stale;
  events_.push_back({time_ns_, stale ? EventKind::kFailsafeOn : EventKind::kFailsafeOff, id, -1,
                     stale ? static_cast<double>(age_ns) * 1e-9 : 0.0});
}

void World::step() {
  events_.clear();
  for (std::size_t i = 0; i < uavs_.size(); ++i) updateFailsafe(uavs_[i], static_cast<int>(i));

  common_gust_.advance();
  const agent::Vec2 wind = meanWind(time_ns_ + dt_ns_);
  for (Uav& u : uavs_) {
    u.gust.advance();
    u.last_gust_mps2 = u.gust.value() + common_gust_.value();
    const agent::Vec2 setpoint = u.failsafe ? agent::Vec2::Zero() : u.setpoint_mps;
    stepLateral(scenario_.dynamics, dt_s_, setpoint, u.last_gust_mps2, u.state);
    // The velocity loop's integrator holds the commanded velocity against the steady drag (PX4's MPC_XY_VEL_I_ACC,
    // ArduPilot's PSC_VELXY_I), so the path stays the lagged response above; what drag changes is the thrust the
    // UAV needs, a = T - k (v - w) + gust, and with it the attitude: T = a + k (v - w) - gust. A UAV holding still
    // in a 5 m/s wind leans into it as if it were accelerating at 0.75 m/s^2 (k = 0.15 1/s).
    u.thrust_mps2 =
        u.state.acceleration_mps2 - u.last_gust_mps2 + scenario_.dynamics.drag_per_s * (u.state.velocity_mps - wind);
    // Heading: the yaw rate follows the commanded one with a first-order lag, like velocity; the failsafe holds
    // the heading. Kept apart from the closed-form turn of heading_rate_std_radps, and exactly 0 while nothing
    // was ever commanded, so an all-round swarm's headings are bit for bit those of a world without yaw control.
    const double yaw_setpoint = u.failsafe ? 0.0 : u.yaw_rate_setpoint_radps;
    u.yaw_rate_radps += (yaw_setpoint - u.yaw_rate_radps) * yaw_response_;
    u.commanded_turn_rad = wrapAngle(u.commanded_turn_rad + u.yaw_rate_radps * dt_s_);
  }

  ++step_;
  time_ns_ = step_ * dt_ns_;
  refreshTruth();
  updateGnssAvailability();
  detectCollisions();
  generateSensors();
}

agent::Vec2 World::meanWind(agent::StampNs at_ns) const {
  const WindSetup& w = scenario_.wind;
  if (w.mean_mps == 0.0) return agent::Vec2::Zero();
  // Meteorological: the direction it comes from, clockwise from north; world x = east, y = north.
  const double from_rad = (w.direction_deg + w.turn_rate_dps * stampSeconds(at_ns)) * M_PI / 180.0;
  return -w.mean_mps * agent::Vec2(std::sin(from_rad), std::cos(from_rad));
}

void World::refreshTruth() {
  // Heading from the closed form psi0 + rate t, not accumulated per step, so it does not drift with round-off.
  const double t_s = stampSeconds(time_ns_);
  for (std::size_t i = 0; i < uavs_.size(); ++i) {
    const Uav& u = uavs_[i];
    UavTruth& t = truth_[i];
    t.position_m = u.state.position_m;
    t.velocity_mps = u.state.velocity_mps;
    t.acceleration_mps2 = u.state.acceleration_mps2;
    t.heading_rad = wrapAngle(u.initial_heading_rad + u.turn_rate_radps * t_s + u.commanded_turn_rad);
    t.failsafe = u.failsafe;
    t.gust_mps2 = u.last_gust_mps2;
    t.thrust_mps2 = u.thrust_mps2;
    t.wind_mps = meanWind(time_ns_);
    positions_[i] = u.state.position_m;
  }
}

void World::updateGnssAvailability() {
  // Every step, not only on GNSS samples: truth and events follow the schedule even when GNSS is not sampled.
  for (std::size_t i = 0; i < uavs_.size(); ++i) {
    Uav& u = uavs_[i];
    const bool available = u.gnss.available(time_ns_);
    if (available != u.gnss_valid) {
      u.gnss_valid = available;
      events_.push_back(
          {time_ns_, available ? EventKind::kGnssRestored : EventKind::kGnssLost, static_cast<int>(i), -1, 0.0});
    }
    truth_[i].gnss_valid = available;
  }
}

void World::detectCollisions() {
  for (const Contact& c : collisions_.update(positions_)) {
    events_.push_back({time_ns_, EventKind::kCollision, c.uav, c.other_uav, c.distance_m});
  }
}

void World::generateSensors() {
  for (std::size_t i = 0; i < uavs_.size(); ++i) {
    Uav& u = uavs_[i];
    UavSensors& out = sensors_[i];
    out = UavSensors{};
    const double heading = truth_[i].heading_rad;
    if (sensorDue(step_, imu_period_steps_)) {
      out.imu = u.imu.sample(time_ns_, u.state.acceleration_mps2, u.thrust_mps2, heading);
    }
    if (sensorDue(step_, mps_period_steps_) && mps_latency_ns_ != kNever) {
      agent::StampNs delay_ns = mps_latency_ns_;
      if (mps_latency_jitter_s_ > 0.0) {  // drawn only then: without jitter the stream is never touched
        const double jitter_s = u.latency_rng.uniform(-mps_latency_jitter_s_, mps_latency_jitter_s_);
        delay_ns = std::max<agent::StampNs>(0, delay_ns + std::llround(jitter_s * 1e9));
      }
      u.in_flight.push_back({time_ns_ + delay_ns, u.mps.scan(time_ns_, static_cast<int>(i), positions_, heading)});
    }
    // The set due first, if it is due (the earlier scan of two due at once: min_element keeps the first minimum).
    const auto first =
        std::min_element(u.in_flight.begin(), u.in_flight.end(),
                         [](const Uav::InFlight& a, const Uav::InFlight& b) { return a.due_ns < b.due_ns; });
    if (first != u.in_flight.end() && first->due_ns <= time_ns_) {
      out.detections = std::move(first->set);
      u.in_flight.erase(first);
    }
    if (sensorDue(step_, gnss_period_steps_)) out.gnss = u.gnss.sample(time_ns_, u.state.position_m);
  }
}

}  // namespace swa::sim

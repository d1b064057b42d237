#pragma once
// The agent's own estimate as the autopilot's external odometry (issue #43), without DDS: which of the agent's states
// the bridge sends, and with what reset counter. A real autopilot leaves SWA's control a few seconds after GNSS is
// lost unless something aids its estimator (PX4: EKF2 invalid after EKF2_NOAID_TOUT, offboard refused; ArduPilot:
// EKF3 without a position 7 s after the last one, EKF failsafe LAND); SWA's agent has exactly that something.
//
// The rules (deploy/README.md, "External odometry"):
//   - the estimate is the vehicle's own agent's (its position and velocity in the swarm's floating frame, axes east
//     and north, with covariance); nothing of another UAV's;
//   - it is fed while the agent has no GNSS (mode kWhileGnssLost, the default; kAlways feeds it always, kOff never),
//     so that the autopilot's own GNSS is never fought, and stops when GNSS returns;
//   - a state is sent only if it is fresh (stamped within stale_after_s of the vehicle's newest attitude sample, on the
//     vehicle's clock), the agent is tracking, every number is finite and the position's standard deviation is at
//     most max_position_std_m: a stale or invalid estimate is never sent;
//   - reset_counter counts the estimate's resets, which the autopilot must not fuse as motion: the agent starting to
//     track again (after initialising or losing its frame) and a restart of the agent's timeline (stamp_resyncs).

#include <cstdint>
#include <optional>

#include "swa/agent/diagnostics.h"
#include "swa/agent/samples.h"

namespace swa::autopilot {

enum class OdometryMode { kOff, kWhileGnssLost, kAlways };

struct OdometryFeedConfig {
  OdometryMode mode = OdometryMode::kWhileGnssLost;
  double stale_after_s = 0.3;        // the agent publishes its state at 10 Hz of sample time
  double max_position_std_m = 20.0;  // beyond it the estimate is no better than none
};

// What goes to the autopilot.
struct Odometry {
  agent::StampNs stamp_ns = 0;
  agent::Vec2 position_m = agent::Vec2::Zero();  // east, north
  agent::Vec2 velocity_mps = agent::Vec2::Zero();
  agent::Vec2 position_var_m2 = agent::Vec2::Zero();  // east, north
  agent::Vec2 velocity_var_m2ps2 = agent::Vec2::Zero();
  std::uint8_t reset_counter = 0;
};

struct OdometryCounters {
  std::uint64_t sent = 0;
  std::uint64_t skipped_gnss = 0;     // the agent has GNSS: the autopilot's own is used
  std::uint64_t skipped_stale = 0;    // older than stale_after_s against the vehicle's newest attitude
  std::uint64_t skipped_invalid = 0;  // not tracking, a non-finite number, too uncertain
  std::uint64_t resets = 0;
  std::uint64_t silences = 0;  // the feed stopped because no fresh state came (expire)
};

class OdometryFeed {
 public:
  explicit OdometryFeed(const OdometryFeedConfig& config);

  // The agent's newest state (swa/uav<I>/state as the agent reports it: its stamp is on the vehicle's clock, the IMU
  // sample it follows), with the vehicle's newest attitude timestamp [ns on the vehicle's clock]: what to send, if
  // anything.
  std::optional<Odometry> onState(const agent::Diagnostics& s, agent::StampNs vehicle_now_ns);
  // No new state by the vehicle's time `vehicle_now_ns`: true once, when the last state sent has become stale (the
  // agent stopped or its states stopped arriving), so that the bridge says the feed stopped and knows it is not
  // feeding. Nothing is ever re-sent: the autopilot's own failsafe decides.
  bool expire(agent::StampNs vehicle_now_ns);
  const OdometryCounters& counters() const { return counters_; }
  // Whether the last state was sent (for the log: the feed started or stopped).
  bool feeding() const { return feeding_; }

 private:
  double staleNs() const;

  OdometryFeedConfig config_;
  OdometryCounters counters_;
  std::uint8_t reset_counter_ = 0;
  bool was_tracking_ = false;
  std::optional<std::uint64_t> resyncs_;
  bool feeding_ = false;
  agent::StampNs last_sent_ns_ = 0;
};

}  // namespace swa::autopilot

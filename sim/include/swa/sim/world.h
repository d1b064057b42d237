#pragma once
// The simulated world (DESIGN §4) as a pure library: N UAVs with lateral dynamics and wind, and the sensors each of
// them carries (IMU + heading, mutual-perception sensor, GNSS). Time is an input: step() advances it by one
// dynamics period; nothing here reads a clock, sleeps, or talks DDS. Deterministic per scenario seed: the same
// scenario and the same command sequence give bit-identical truth and samples (see random.h for the streams).
//
// Step protocol (lockstep or realtime alike):
//   World w(scenario);                 // t = 0: UAVs placed, samples due at t = 0 in w.sensors()
//   loop: deliver w.sensors() to the agents; w.command(i, cmd) for the answers; w.step();
// step() applies the latest command of each UAV over [t, t + dt), then produces the samples due at t + dt.
//
// Conventions: world frame W = every UAV's stable frame S (DESIGN §2); UAV ids are 0..N-1 and index every vector
// below; sample stamps are k * round(1e9 / dynamics.rate_hz) ns (timing.h, which also documents sensor rates).

#include <cstdint>
#include <optional>
#include <vector>

#include "swa/agent/geometry.h"
#include "swa/agent/samples.h"
#include "swa/sim/collision_monitor.h"
#include "swa/sim/gnss_model.h"
#include "swa/sim/imu_model.h"
#include "swa/sim/mps_model.h"
#include "swa/sim/ou_process.h"
#include "swa/sim/random.h"
#include "swa/sim/scenario.h"
#include "swa/sim/uav_dynamics.h"

namespace swa::sim {

struct UavTruth {
  int id = 0;
  agent::Vec2 position_m = agent::Vec2::Zero();
  agent::Vec2 velocity_mps = agent::Vec2::Zero();
  agent::Vec2 acceleration_mps2 = agent::Vec2::Zero();  // achieved over the last step (what the accelerometer reads)
  double heading_rad = 0.0;                             // (-pi, pi], body x from world x, counter-clockwise
  bool gnss_valid = true;                               // the dropout schedule at this time (also when not sampled)
  bool failsafe = false;                                // braking to hover during the last step
  agent::Vec2 gust_mps2 = agent::Vec2::Zero();          // wind acceleration applied in the last step (own + common)
  agent::Vec2 thrust_mps2 = agent::Vec2::Zero();        // the thrust's lateral share (what the tilt encodes)
  agent::Vec2 wind_mps = agent::Vec2::Zero();           // the mean wind now (the same for every UAV)
};

enum class EventKind { kGnssLost, kGnssRestored, kCollision, kFailsafeOn, kFailsafeOff };

// stamp_ns: the sim time at which the condition was detected (failsafe: start of the step it applies to; GNSS and
// collisions: the end of the step, = time_ns()). other_uav: the second UAV of a collision, -1 otherwise.
// value: collision distance (m); command age (s) for kFailsafeOn; 0 otherwise.
struct Event {
  agent::StampNs stamp_ns = 0;
  EventKind kind = EventKind::kCollision;
  int uav = 0;
  int other_uav = -1;
  double value = 0.0;
};

// What UAV i's sensors deliver at one step; an empty optional means "no sample from that sensor now". Detection sets
// are stamped at measurement time and delivered mps.latency_s later (rounded up to the next step), so with latency
// the stamp of a delivered set is older than time_ns(). With mps.latency_jitter_s each set's delay varies and sets can
// arrive out of stamp order; at most one set is delivered per step, the one due first (a second one due in the same
// step waits for the next).
struct UavSensors {
  std::optional<agent::ImuSample> imu;
  std::optional<agent::DetectionSet> detections;
  std::optional<agent::GnssSample> gnss;
};

class World {
 public:
  // Validates nothing (the scenario loader does), except what would make the model undefined: throws
  // std::invalid_argument if dynamics.rate_hz is not positive and finite or uav_count is negative.
  // Places the UAVs at rest on a hexagonal lattice (lattice.h) with uniform jitter in a disc of radius
  // formation.position_jitter_m; headings uniform in [-pi, pi) (kRandom) or 0, constant turn rates
  // N(0, heading_rate_std_radps^2).
  explicit World(const Scenario& scenario);

  agent::StampNs time_ns() const { return time_ns_; }
  std::int64_t step_index() const { return step_; }
  int uav_count() const { return static_cast<int>(uavs_.size()); }
  const Scenario& scenario() const { return scenario_; }

  // Samples due at time_ns(); valid after construction and after each step().
  const std::vector<UavSensors>& sensors() const { return sensors_; }

  // Latest velocity setpoint of that UAV (stable/world frame). Its age for the failsafe is measured from the sim
  // time at which it arrives (time_ns() now), like an autopilot's offboard timeout, not from cmd.stamp_ns.
  // A setpoint with a non-finite velocity is dropped (the previous one stays in force and keeps ageing).
  // Throws std::out_of_range for an unknown UAV.
  void command(int uav, const agent::VelocityCommand& cmd);

  // Advances by one dynamics period, then generates the samples due at the new time. A UAV whose latest setpoint is
  // older than dynamics.failsafe_timeout_s at the start of the step (or that never received one, once the timeout
  // has passed since t = 0) is commanded to hover (v = 0) for the step.
  void step();

  const std::vector<UavTruth>& truth() const { return truth_; }
  const std::vector<Event>& events() const { return events_; }  // raised by the last step() (or construction)
  int collisions() const { return collisions_.onsets(); }       // cumulative collision onsets (collision_monitor.h)
  bool finished() const { return time_ns_ >= duration_ns_; }

 private:
  struct Uav {
    Uav(const KinematicState& initial, double heading_rad, double turn_rate, OuProcess2 own_gust, ImuModel imu_model,
        MpsModel mps_model, GnssModel gnss_model, Rng latency_stream);

    KinematicState state;
    double initial_heading_rad = 0.0;
    double turn_rate_radps = 0.0;
    OuProcess2 gust;
    ImuModel imu;
    MpsModel mps;
    GnssModel gnss;
    Rng latency_rng;
    struct InFlight {
      agent::StampNs due_ns = 0;
      agent::DetectionSet set;
    };
    std::vector<InFlight> in_flight;  // measured, waiting for their latency to pass; in scan order
    agent::Vec2 setpoint_mps = agent::Vec2::Zero();
    double yaw_rate_setpoint_radps = 0.0;    // clamped to dynamics.max_yaw_rate_radps
    double yaw_rate_radps = 0.0;             // the lagged response
    double commanded_turn_rad = 0.0;         // heading turned by yaw commands, on top of the scenario's own turn
    agent::StampNs setpoint_arrival_ns = 0;  // t = 0 stands for "none yet": the timeout then runs from the start
    agent::Vec2 last_gust_mps2 = agent::Vec2::Zero();
    agent::Vec2 thrust_mps2 = agent::Vec2::Zero();  // lateral thrust per unit mass over the last step
    bool failsafe = false;
    bool gnss_valid = true;
  };

  static Uav makeUav(const Scenario& scenario, int id, const agent::Vec2& slot_m, double dt_s);
  void updateFailsafe(Uav& uav, int id);
  void refreshTruth();
  void updateGnssAvailability();
  void detectCollisions();
  void generateSensors();
  agent::Vec2 meanWind(agent::StampNs at_ns) const;  // air velocity of the mean wind in the world frame

  Scenario scenario_;
  agent::StampNs dt_ns_;
  double dt_s_;
  agent::StampNs duration_ns_;
  agent::StampNs failsafe_timeout_ns_;
  agent::StampNs mps_latency_ns_;
  double mps_latency_jitter_s_;
  std::int64_t imu_period_steps_;
  std::int64_t mps_period_steps_;
  std::int64_t gnss_period_steps_;

  agent::StampNs time_ns_ = 0;
  std::int64_t step_ = 0;
  OuProcess2 common_gust_;
  double yaw_response_;  // 1 - exp(-dt / yaw_lag_s): the yaw rate's share of its error closed per step
  std::vector<Uav> uavs_;
  CollisionMonitor collisions_;
  std::vector<agent::Vec2> positions_;  // scratch: truth positions in id order, for the MPS and collisions
  std::vector<UavTruth> truth_;
  std::vector<UavSensors> sensors_;
  std::vector<Event> events_;
};

}  // namespace swa::sim

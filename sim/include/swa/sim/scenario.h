#pragma once
// One scenario file describes a whole run: the swarm, the world, the sensors and the agents' parameters. Defaults
// are DESIGN §4 (the simulator model) and the paper's GNSS-loss experiment. Units are in the names.

#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "swa/agent/config.h"
#include "swa/autopilot/odometry_feed.h"
#include "swa/px4/release.h"

namespace swa::sim {

enum class ClockMode { kLockstep, kRealtime };
enum class HeadingMode { kRandom, kZero };
enum class MpsNoiseModel { kIsotropic, kRangeBearing };
// How the agents reach their vehicles in swa_sim: directly (the simulator reads cmd_vel and publishes imu), or through
// PX4's uXRCE-DDS topics (vehicle.px4_release) or ArduPilot's AP_DDS ones, with the simulator playing each UAV's
// autopilot and one swa_px4_bridge per agent.
enum class VehicleInterface { kDirect, kPx4, kArdupilot };
// Where the agents' GNSS comes from with vehicle.interface = px4 or ardupilot: the simulator's own swa/uav<i>/gnss
// (swa), or each UAV's autopilot stand-in as a real one reports it (PX4: vehicle_gps_position, vehicle_local_position;
// ArduPilot: navsat), forwarded by the bridge (autopilot).
enum class GnssSource { kSwa, kAutopilot };

struct FormationSetup {
  double spacing_m = 10.0;         // initial neighbour spacing; also the agents' formation.radius_m unless overridden
  double position_jitter_m = 1.0;  // initial position error around the lattice slots
};

struct DynamicsSetup {
  double rate_hz = 100.0;
  double velocity_lag_s = 1.0;  // first-order response of velocity to the command
  double speed_limit_mps = 5.0;
  double failsafe_timeout_s = 0.5;  // commands older than this: the UAV brakes to hover
  HeadingMode heading = HeadingMode::kRandom;
  double heading_rate_std_radps = 0.0;  // per-UAV constant turn rate (0 = constant heading)
  double yaw_lag_s = 0.3;               // first-order response of the yaw rate to the commanded one
  double max_yaw_rate_radps = 1.0;      // commanded yaw rates are clamped to this (the vehicle's limit)
  // Linear aerodynamic drag per unit mass on the air-relative velocity, a_drag = -k (v - w) (issue #44). Default:
  // PX4's EKF2_MCOEF (src/modules/ekf2/params_drag.yaml, 0.15 1/s), the rotor momentum drag PX4 assumes for a
  // small multirotor. The autopilot's velocity loop holds the commanded velocity against it (its integrator), so
  // drag changes the attitude the UAV flies with, not its path: see World::step.
  double drag_per_s = 0.15;
};

struct WindSetup {
  double gust_std = 0.2;  // m/s^2, per-UAV Ornstein-Uhlenbeck acceleration
  double gust_corr_s = 5.0;
  double common_std = 0.0;  // m/s^2, the same OU gust for every UAV (moves the swarm as a block)
  double common_corr_s = 20.0;
  // The mean wind, the same for every UAV (issue #44): speed, and the direction it blows from, clockwise from north
  // (the meteorological convention: 270 = a westerly, blowing east), turning at turn_rate_dps.
  double mean_mps = 0.0;
  double direction_deg = 270.0;
  double turn_rate_dps = 0.0;  // deg/s, clockwise positive like the direction
};

struct ImuSetup {
  double rate_hz = 100.0;
  double bias_std = 0.05;  // m/s^2 of derived acceleration, constant per UAV
  double noise_std = 1.5;  // m/s^2 white (sqrt of R_a)
  double heading_noise_std_rad = 0.005;
  // The compass's own error (issue #44): a constant per-UAV offset (a magnetometer calibrated on another airframe,
  // the motors' field) and a slow random walk on top (temperature, currents), both 0 by default: an ideal compass.
  double heading_bias_std_rad = 0.0;
  double heading_bias_walk_radps = 0.0;  // rad/sqrt(s): the std of the walk's change over one second
  // Which acceleration the agents fuse (agent.focal.imu_source unless given): the simulator publishes both.
  agent::ImuSource source = agent::ImuSource::kAccelerometer;
  // The accelerometer part (issue #44), read with the autopilot's attitude estimate. Its constant per-UAV tilt
  // error becomes an acceleration bias of g x the error; the default 0.005 rad is the tilt source's bias_std (0.05
  // m/s^2 / g), so that both sources start from the same attitude error. The accelerometer's own errors are a
  // MEMS part's (TDK InvenSense ICM-20948, DS-000189 rev 1.3, table 2, as on Pixhawk-class boards): zero-g offset
  // change 0.8 mg/degC over a 20 degC difference from the calibration = 16 mg = 0.157 m/s^2 per axis, constant;
  // white noise: PX4's EKF2_ACC_NOISE (0.35 m/s^2; src/modules/ekf2/module.yaml, before v1.15 ekf2_params.c), what
  // the autopilot assumes in flight, motors' vibration included (the part alone, 230 ug/sqrt(Hz) over 50 Hz, is
  // 0.016 m/s^2).
  double attitude_error_std_rad = 0.005;
  double accel_bias_std_mps2 = 0.157;
  double accel_noise_std_mps2 = 0.35;
};

struct MpsSetup {
  double rate_hz = 10.0;
  double range_m = 40.0;
  double fov_deg = 360.0;
  double mount_deg = 0.0;  // centre of the field of view, counter-clockwise from body x
  MpsNoiseModel noise_model = MpsNoiseModel::kIsotropic;
  double noise_var_m2 = 0.1;  // isotropic model (R_o)
  double range_std_m = 0.2;   // range/bearing model
  double bearing_std_rad = 0.01;
  double miss_probability = 0.05;
  double clutter_rate = 0.0;  // mean false positives per scan, uniform in the sensing disc
  bool ids = true;
  double latency_s = 0.0;
  // Each set's delay is latency_s plus a uniform draw in [-latency_jitter_s, +latency_jitter_s] (never below 0), so a
  // later scan can arrive before an earlier one (issue #44).
  double latency_jitter_s = 0.0;
};

// An extra GNSS outage of one UAV: no fix in [start_s, end_s); end_s = +inf means never restored.
struct GnssWindow {
  int uav = 0;
  double start_s = 0.0;
  double end_s = std::numeric_limits<double>::infinity();
};

struct GnssSetup {
  double rate_hz = 10.0;
  double std_m = 0.5;
  double dropout_start_s = 10.0;                                   // every UAV loses GNSS at this time ...
  double dropout_end_s = std::numeric_limits<double>::infinity();  // ... until this time
  std::vector<int> keep_uavs;  // UAVs that never lose GNSS in the common window (e.g. one anchored member)
  // Per-UAV outages on top of the common window: a UAV has no GNSS while it is inside the common window (unless
  // it is in keep_uavs) or inside any of its own windows. Windows may overlap; keep_uavs does not exempt them.
  std::vector<GnssWindow> windows;
};

struct VehicleSetup {
  VehicleInterface interface = VehicleInterface::kDirect;
  double com_of_loss_t_s = 1.0;  // PX4's COM_OF_LOSS_T (default 1 s in v1.15-v1.17): offboard lost -> Hold
  double guid_timeout_s = 3.0;   // ArduPilot's GUID_TIMEOUT (Copter default 3 s): no cmd_vel this long -> stop
  px4::Release px4_release = px4::kNewestRelease;  // the layouts and topic names the PX4 stand-in speaks
  GnssSource gnss_source = GnssSource::kSwa;
  // Issue #43: whether the stand-ins model the autopilot's estimator (PX4's EKF2, ArduPilot's EKF3 and EKF failsafe),
  // which leaves SWA's control a few seconds after GNSS is lost unless external odometry is fused; false: an estimate
  // always valid, as before.
  bool estimator = true;
  double ekf2_noaid_tout_s = 5.0;  // PX4's EKF2_NOAID_TOUT (5 s in v1.15 to v1.17)
  int ekf2_ev_ctrl = 5;            // PX4's EKF2_EV_CTRL as the pre-flight table sets it (PX4: 15 in v1.15, 0 after)
  bool ap_external_nav = true;     // ArduPilot: external navigation once GPS is lost (the pre-flight table's setup)
  // When swa_launch's bridges feed their agent's estimate as external odometry (swa_px4_bridge --odometry).
  autopilot::OdometryMode odometry = autopilot::OdometryMode::kWhileGnssLost;
  // Issue #46, PX4 with GNSS from the autopilot: at px4_origin_shift_at_s every stand-in moves its local origin this
  // far east and north of the old one and re-bases x, y on it, as EKF2 does when its global origin is re-set in flight.
  double px4_origin_shift_at_s = std::numeric_limits<double>::infinity();  // never
  double px4_origin_shift_east_m = 0.0, px4_origin_shift_north_m = 0.0;
};

struct ClockSetup {
  ClockMode mode = ClockMode::kLockstep;
  double speed = 1.0;  // realtime factor
};

struct Scenario {
  int uav_count = 8;
  std::uint64_t seed = 1;
  double duration_s = 120.0;
  FormationSetup formation;
  DynamicsSetup dynamics;
  WindSetup wind;
  ImuSetup imu;
  MpsSetup mps;
  GnssSetup gnss;
  ClockSetup clock;
  VehicleSetup vehicle;
  agent::AgentConfig agent;
};

// The time from which drift, displacement and ANEES are measured (monitor::MetricsConfig::window_start_s): the
// common GNSS loss if it happens during the run, else 0. Shared by swa_batch and swa_monitor so both score a run
// over the same window.
inline double driftWindowStart(const Scenario& s) {
  const double t = s.gnss.dropout_start_s;
  return (std::isfinite(t) && t < s.duration_s) ? t : 0.0;
}

// When the agents' mission begins (agent.mission.start): at its time, or at the first GNSS sample without a fix, the
// first sample at or after the common dropout (a sample every 1/gnss.rate_hz from 0). NaN when it never does: no
// plan, no GNSS loss within the run, or no GNSS samples.
inline double missionStart(const Scenario& s) {
  const agent::MissionConfig& m = s.agent.mission;
  const double never = std::numeric_limits<double>::quiet_NaN();
  if (m.legs.empty()) return never;
  if (m.start == agent::MissionStart::kTime) return m.start_s < s.duration_s ? m.start_s : never;
  const double t = s.gnss.dropout_start_s;
  if (!std::isfinite(t) || t >= s.duration_s || !(s.gnss.rate_hz > 0.0)) return never;
  return std::ceil(t * s.gnss.rate_hz - 1e-9) / s.gnss.rate_hz;
}

}  // namespace swa::sim

#include "swa/sim/scenario_io.h"

#include <limits>
#include <string>
#include <vector>

#include "scenario_rules.h"
#include "swa/agent/config_io.h"
#include "swa/params/table.h"

namespace swa::sim {

namespace {

using params::closed;
using params::closedOpen;
using params::formatYamlNumber;
using params::openClosed;
using params::Values;

constexpr int kMaxUavs = 256;
constexpr double kMaxTime_s = 1e6;
constexpr double kInf = std::numeric_limits<double>::infinity();
// A re-set EKF origin is a place the vehicle's receiver has seen: within 100 km of the old one.
constexpr double kMaxOriginShiftM = 1e5;

// gnss.windows: a list of {uav, start_s, end_s} records.
params::Spec windowsSpec() {
  params::Spec s = params::makeSpec("gnss.windows", params::Kind::kRecordList, "s");
  s.meaning = "extra outages of single UAVs on top of the common one (keep_uavs does not exempt them)";
  s.fields = {params::makeSpec("uav", params::Kind::kInteger, "", closed(0, kMaxUavs - 1)),
              params::makeSpec("start_s", params::Kind::kReal, "s", closed(0, kMaxTime_s)),
              params::makeSpec("end_s", params::Kind::kReal, "s", openClosed(0, kMaxTime_s))};
  s.fields[2].allow_infinity = true;
  s.fields[2].default_value = kInf;
  s.earlier = "start_s";
  s.later = "end_s";
  s.order_why = "the outage would be empty (leave end_s out for one that never ends)";
  s.example = "{uav: 3, start_s: 20, end_s: 40}";
  s.expected = "a list of outage windows such as [" + s.example + "] or [] (end_s optional: .inf = never restored)";
  s.range_text =
      "list of {uav, start_s, end_s}: uav in [0, uav_count), 0 <= start_s < end_s <= " + formatYamlNumber(kMaxTime_s) +
      " or .inf";
  s.comment = "per-UAV outages {uav, start_s, end_s} (end_s .inf = never restored)";
  s.type_name = "window list";
  return s;
}

params::Table<Scenario> makeTable() {
  params::Table<Scenario> t("SWA scenario", "scenario", "uav_count: 8", "uav_count=16", scenarioRuleNotes());
  SWA_PARAM(t, number, uav_count, "", closed(1, kMaxUavs), "number of UAVs in the swarm (indices 0 .. uav_count-1)");
  SWA_PARAM(t, seed, seed, "random seed of the world (initial positions, headings, wind, sensor noise)");
  SWA_PARAM(t, number, duration_s, "s", openClosed(0, 86400), "simulated time the run lasts");

  SWA_PARAM(t, number, formation.spacing_m, "m", openClosed(0, 1000),
            "initial neighbour spacing; also agent.formation.radius_m unless that is given");
  SWA_PARAM(t, number, formation.position_jitter_m, "m", closed(0, 1000),
            "initial position error around the lattice slots");

  SWA_PARAM(t, number, dynamics.rate_hz, "Hz", openClosed(0, 10000),
            "simulation step rate; every sensor rate must divide it");
  SWA_PARAM(t, number, dynamics.velocity_lag_s, "s", openClosed(0, 60),
            "first-order time constant of the velocity response to the command");
  SWA_PARAM(t, number, dynamics.speed_limit_mps, "m/s", openClosed(0, 100), "horizontal speed limit of a UAV");
  SWA_PARAM(t, number, dynamics.failsafe_timeout_s, "s", openClosed(0, 60),
            "a UAV whose commands are older than this brakes to hover");
  SWA_PARAM(
      t, choice, dynamics.heading,
      std::vector<std::pair<HeadingMode, std::string>>{{HeadingMode::kRandom, "random"}, {HeadingMode::kZero, "zero"}},
      "initial heading of each UAV: random per UAV, or zero (body = world axes)");
  SWA_PARAM(t, number, dynamics.heading_rate_std_radps, "rad/s", closed(0, 10),
            "std of a per-UAV constant turn rate (0 = constant heading)");
  SWA_PARAM(t, number, dynamics.yaw_lag_s, "s", openClosed(0, 60),
            "first-order time constant of the yaw rate's response to the commanded yaw rate");
  SWA_PARAM(t, number, dynamics.max_yaw_rate_radps, "rad/s", openClosed(0, 100),
            "commanded yaw rates are clamped to +- this (the vehicle's limit)");

  SWA_PARAM(t, number, dynamics.drag_per_s, "1/s", closed(0, 5),
            "linear drag per unit mass on the air-relative velocity, -k (v - wind); the velocity loop holds the path "
            "against it, so it changes the attitude flown (what the tilt shows). Default: PX4's EKF2_MCOEF, a small "
            "multirotor's rotor momentum drag");
  SWA_PARAM(t, number, wind.mean_mps, "m/s", closed(0, 30), "speed of the mean wind, the same for every UAV (0: calm)");
  SWA_PARAM(t, number, wind.direction_deg, "deg", closed(-360, 360),
            "where the mean wind blows from, clockwise from north (270: a westerly, blowing east)");
  SWA_PARAM(t, number, wind.turn_rate_dps, "deg/s", closed(-10, 10),
            "the mean wind's direction turns at this rate, clockwise positive (0: steady)");
  SWA_PARAM(t, number, wind.gust_std, "m/s^2", closed(0, 100),
            "std of the per-UAV Ornstein-Uhlenbeck gust acceleration");
  SWA_PARAM(t, number, wind.gust_corr_s, "s", openClosed(0, 3600), "correlation time of the per-UAV gust");
  SWA_PARAM(t, number, wind.common_std, "m/s^2", closed(0, 100),
            "std of the gust common to every UAV (moves the swarm as a block)");
  SWA_PARAM(t, number, wind.common_corr_s, "s", openClosed(0, 3600), "correlation time of the common gust");

  SWA_PARAM(t, number, imu.rate_hz, "Hz", openClosed(0, 10000), "IMU sample rate; must divide dynamics.rate_hz");
  SWA_PARAM(t, number, imu.bias_std, "m/s^2", closed(0, 100),
            "std of the constant per-UAV bias of the tilt-derived acceleration (what an imu.source tilt agent reads)");
  SWA_PARAM(t, number, imu.noise_std, "m/s^2", closed(0, 100),
            "std of the white noise of the tilt-derived acceleration (what an imu.source tilt agent reads)");
  SWA_PARAM(t, number, imu.heading_noise_std_rad, "rad", closed(0, 1), "std of the heading (magnetometer) noise");
  SWA_PARAM(t, number, imu.heading_bias_std_rad, "rad", closed(0, 1),
            "std of the compass's constant per-UAV heading bias (0: none); a magnetometer's several degrees");
  SWA_PARAM(t, number, imu.heading_bias_walk_radps, "rad/sqrt(s)", closed(0, 0.1),
            "random walk of the compass's heading bias: the std of its change over one second (0: none)");
  SWA_PARAM(t, choice, imu.source,
            std::vector<std::pair<agent::ImuSource, std::string>>{{agent::ImuSource::kTilt, "tilt"},
                                                                  {agent::ImuSource::kAccelerometer, "accelerometer"}},
            "the acceleration the agents fuse (also agent.focal.imu_source unless that is given): tilt (the attitude "
            "x q_c: the thrust only) or accelerometer (the specific force turned by the attitude: every push); the "
            "simulator publishes both");
  SWA_PARAM(t, number, imu.attitude_error_std_rad, "rad", closed(0, 0.2),
            "std of the constant per-UAV error of the attitude the accelerometer is read with (an acceleration bias "
            "of g x it)");
  SWA_PARAM(t, number, imu.accel_bias_std_mps2, "m/s^2", closed(0, 10),
            "std of the accelerometer's constant per-UAV bias, per axis (default: ICM-20948's zero-g drift over "
            "20 degC)");
  SWA_PARAM(t, number, imu.accel_noise_std_mps2, "m/s^2", closed(0, 10),
            "std of the accelerometer's white noise per axis and sample (default: PX4's EKF2_ACC_NOISE, vibration "
            "included)");

  SWA_PARAM(t, number, mps.rate_hz, "Hz", openClosed(0, 10000),
            "mutual-perception sensor scan rate; must divide dynamics.rate_hz");
  SWA_PARAM(t, number, mps.range_m, "m", openClosed(0, 10000), "neighbours farther than this are not detected");
  SWA_PARAM(t, number, mps.fov_deg, "deg", openClosed(0, 360),
            "horizontal field of view, centred on mps.mount_deg; also agent.sensor.fov_deg unless that is given");
  SWA_PARAM(t, number, mps.mount_deg, "deg", closed(-360, 360),
            "centre of the field of view, counter-clockwise from body x; also agent.sensor.mount_deg unless given");
  SWA_PARAM(t, choice, mps.noise_model,
            std::vector<std::pair<MpsNoiseModel, std::string>>{{MpsNoiseModel::kIsotropic, "isotropic"},
                                                               {MpsNoiseModel::kRangeBearing, "range_bearing"}},
            "isotropic (noise_var_m2, UVDAR-like) or range_bearing (range_std_m/bearing_std_rad, LiDAR-like)");
  SWA_PARAM(t, number, mps.noise_var_m2, "m^2", closed(0, 100),
            "isotropic model: variance of each position coordinate (R_o)");
  SWA_PARAM(t, number, mps.range_std_m, "m", closed(0, 100), "range_bearing model: range noise std");
  SWA_PARAM(t, number, mps.bearing_std_rad, "rad", closed(0, 1), "range_bearing model: bearing noise std");
  SWA_PARAM(t, number, mps.miss_probability, "", closedOpen(0, 1),
            "probability that a neighbour in range is not detected in a scan");
  SWA_PARAM(t, number, mps.clutter_rate, "1/scan", closed(0, 1000),
            "mean number of false detections per scan, uniform in the sensing disc");
  SWA_PARAM(t, flag, mps.ids, "true: detections carry the target's ID (UVDAR-like); false: anonymous (LiDAR-like)");
  SWA_PARAM(t, number, mps.latency_s, "s", closed(0, 10), "delay between a scan and the delivery of its detections");
  SWA_PARAM(t, number, mps.latency_jitter_s, "s", closed(0, 10),
            "each detection set's delay is latency_s plus a uniform draw in +-this (never below 0): sets can arrive "
            "out of order");

  SWA_PARAM(t, number, gnss.rate_hz, "Hz", openClosed(0, 10000), "GNSS fix rate; must divide dynamics.rate_hz");
  SWA_PARAM(t, number, gnss.std_m, "m", closed(0, 100), "std of each horizontal coordinate of a fix");
  SWA_PARAM(t, number, gnss.dropout_start_s, "s", closed(0, kMaxTime_s),
            "every UAV (except keep_uavs) loses GNSS at this time");
  SWA_PARAM(t, number, gnss.dropout_end_s, "s", openClosed(0, kMaxTime_s),
            "GNSS comes back at this time; .inf (default) = never", /*allow_infinity=*/true);
  SWA_PARAM(t, intList, gnss.keep_uavs, closed(0, kMaxUavs - 1),
            "UAVs that never lose GNSS, e.g. [0] for one anchored member; indices in [0, uav_count)",
            "a list of UAV indices such as [0] or [] (indices in [0, uav_count))", "UAV indices in [0, uav_count)");
  t.add(
      windowsSpec(),
      [](const Scenario& s) {
        std::vector<params::Record> out;
        for (const GnssWindow& w : s.gnss.windows) out.push_back({static_cast<double>(w.uav), w.start_s, w.end_s});
        return params::Value(out);
      },
      [](Scenario& s, const params::Value& v) {
        s.gnss.windows.clear();
        for (const params::Record& r : std::get<std::vector<params::Record>>(v)) {
          s.gnss.windows.push_back({static_cast<int>(r[0]), r[1], r[2]});
        }
      });

  SWA_PARAM(t, choice, clock.mode,
            std::vector<std::pair<ClockMode, std::string>>{{ClockMode::kLockstep, "lockstep"},
                                                           {ClockMode::kRealtime, "realtime"}},
            "lockstep: deterministic, as fast as the agents answer; realtime: wall-clock pacing");
  SWA_PARAM(t, number, clock.speed, "", openClosed(0, 1000), "realtime mode: simulated seconds per wall-clock second");

  SWA_PARAM(t, choice, vehicle.interface,
            std::vector<std::pair<VehicleInterface, std::string>>{{VehicleInterface::kDirect, "direct"},
                                                                  {VehicleInterface::kPx4, "px4"},
                                                                  {VehicleInterface::kArdupilot, "ardupilot"}},
            "swa_sim: direct (agents' cmd_vel and imu), px4 (each UAV a PX4 autopilot on rt/px4_<i>/fmu/...) or "
            "ardupilot (each UAV an ArduPilot Copter on rt/ap/v<i+1>/...), reached through one swa_px4_bridge per "
            "agent (swa_launch starts them); swa_batch closes the loop directly");
  SWA_PARAM(t, number, vehicle.com_of_loss_t_s, "s", openClosed(0, 60),
            "px4: PX4's COM_OF_LOSS_T, offboard signal silent this long -> failsafe Hold");
  SWA_PARAM(t, number, vehicle.guid_timeout_s, "s", openClosed(0, 60),
            "ardupilot: ArduPilot's GUID_TIMEOUT, no cmd_vel this long in GUIDED -> the vehicle stops and holds");
  SWA_PARAM(t, choice, vehicle.px4_release,
            std::vector<std::pair<px4::Release, std::string>>{
                {px4::Release::kV1_15, "v1.15"}, {px4::Release::kV1_16, "v1.16"}, {px4::Release::kV1_17, "v1.17"}},
            "px4: the PX4 release the stand-ins play (message layouts, versioned topic names such as "
            "vehicle_status_v1); swa_launch gives every bridge the same --px4-release");
  SWA_PARAM(
      t, choice, vehicle.gnss_source,
      std::vector<std::pair<GnssSource, std::string>>{{GnssSource::kSwa, "swa"}, {GnssSource::kAutopilot, "autopilot"}},
      "px4, ardupilot: swa (the simulator publishes swa/uav<i>/gnss) or autopilot (each PX4 stand-in reports "
      "its fix on vehicle_gps_position and vehicle_local_position, losing both when the scenario drops GNSS; "
      "each ArduPilot stand-in on navsat, silent while GNSS is dropped; the bridges forward them as "
      "swa/uav<i>/gnss)");
  SWA_PARAM(t, choice, vehicle.odometry,
            std::vector<std::pair<autopilot::OdometryMode, std::string>>{
                {autopilot::OdometryMode::kWhileGnssLost, "gnss-loss"},
                {autopilot::OdometryMode::kAlways, "always"},
                {autopilot::OdometryMode::kOff, "off"}},
            "px4, ardupilot: when swa_launch's bridges feed their agent's estimate to the autopilot as external "
            "odometry (swa_px4_bridge --odometry): gnss-loss (while the agent has no GNSS), always, or off");
  SWA_PARAM(t, flag, vehicle.estimator,
            "px4, ardupilot: true: the stand-ins model the autopilot's estimator, as a real one leaves SWA's control "
            "once GNSS is lost unless it fuses the bridge's odometry (PX4: EKF2 invalid after EKF2_NOAID_TOUT, "
            "offboard refused, failsafe Altitude mode; ArduPilot: EKF3 without a position 7 s after the last one, EKF "
            "failsafe LAND 1 s later, GUIDED refused); false: an estimate that is always valid");
  SWA_PARAM(t, number, vehicle.ekf2_noaid_tout_s, "s", closed(0.5, 10),
            "px4: PX4's EKF2_NOAID_TOUT, dead reckoning without GNSS or external vision this long -> local "
            "position and velocity invalid (PX4's default 5 s)");
  SWA_PARAM(t, number, vehicle.ekf2_ev_ctrl, "", closed(0, 15),
            "px4: PX4's EKF2_EV_CTRL, what EKF2 fuses of vehicle_visual_odometry: bit 0 horizontal position, 1 "
            "vertical position, 2 velocity, 3 yaw; 5 as the pre-flight table asks (PX4's default: 15 in v1.15, 0 "
            "from v1.16, which fuses nothing)");
  SWA_PARAM(t, number, vehicle.px4_origin_shift_at_s, "s", openClosed(0, kMaxTime_s),
            "px4 with vehicle.gnss_source = autopilot: at this time every PX4 stand-in moves its local origin as "
            "EKF2 does when its global origin is re-set in flight (issue #46): ref_lat, ref_lon to the point "
            "vehicle.px4_origin_shift_east_m and _north_m from the old one, ref_timestamp to now, and x, y re-based "
            "on it; the bridges bring the positions back into the first origin's frame; .inf (default) = never",
            /*allow_infinity=*/true);
  SWA_PARAM(t, number, vehicle.px4_origin_shift_east_m, "m", closed(-kMaxOriginShiftM, kMaxOriginShiftM),
            "px4: how far east of the old local origin the new one lies (vehicle.px4_origin_shift_at_s)");
  SWA_PARAM(t, number, vehicle.px4_origin_shift_north_m, "m", closed(-kMaxOriginShiftM, kMaxOriginShiftM),
            "px4: how far north of the old local origin the new one lies (vehicle.px4_origin_shift_at_s)");
  SWA_PARAM(t, flag, vehicle.ap_external_nav,
            "ardupilot: whether EKF3 takes the bridge's ap/tf odometry once GPS is lost (VISO_TYPE 1, source set 2 "
            "with EK3_SRC2_POSXY 6, switched to on GPS loss: the pre-flight table); false: ArduPilot's defaults, "
            "VISO_TYPE 0");

  t.mount(
      "agent", agent::configTable(), [](auto& s) -> auto& { return s.agent; },
      "the agents' configuration (swa_agent --parameters); formation.radius_m as used");
  params::Schema& schema = t.schema();
  schema.checks = scenarioChecks();
  for (params::Check& c : agent::configChecks("agent.")) schema.checks.push_back(std::move(c));
  // After the mount, which brought the agent's own (agent.formation.k, ...).
  schema.applies.insert(
      schema.applies.end(),
      {
          {"clock.speed", "clock.mode", {"realtime"}, "realtime mode"},
          {"mps.noise_var_m2", "mps.noise_model", {"isotropic"}, "the isotropic noise model"},
          {"mps.range_std_m", "mps.noise_model", {"range_bearing"}, "the range_bearing noise model"},
          {"mps.bearing_std_rad", "mps.noise_model", {"range_bearing"}, "the range_bearing noise model"},
          {"vehicle.com_of_loss_t_s", "vehicle.interface", {"px4"}, "the px4 vehicle interface"},
          {"vehicle.px4_release", "vehicle.interface", {"px4"}, "the px4 vehicle interface"},
          {"vehicle.gnss_source", "vehicle.interface", {"px4", "ardupilot"}, "an autopilot vehicle interface"},
          {"vehicle.guid_timeout_s", "vehicle.interface", {"ardupilot"}, "the ardupilot vehicle interface"},
          {"vehicle.estimator", "vehicle.interface", {"px4", "ardupilot"}, "an autopilot vehicle interface"},
          {"vehicle.odometry", "vehicle.interface", {"px4", "ardupilot"}, "an autopilot vehicle interface"},
          {"vehicle.ekf2_noaid_tout_s", "vehicle.interface", {"px4"}, "the px4 vehicle interface"},
          {"vehicle.ekf2_ev_ctrl", "vehicle.interface", {"px4"}, "the px4 vehicle interface"},
          {"vehicle.ap_external_nav", "vehicle.interface", {"ardupilot"}, "the ardupilot vehicle interface"},
          {"vehicle.px4_origin_shift_at_s", "vehicle.interface", {"px4"}, "the px4 vehicle interface"},
          {"vehicle.px4_origin_shift_east_m", "vehicle.interface", {"px4"}, "the px4 vehicle interface"},
          {"vehicle.px4_origin_shift_north_m", "vehicle.interface", {"px4"}, "the px4 vehicle interface"},
          {"vehicle.px4_origin_shift_at_s", "vehicle.gnss_source", {"autopilot"}, "GNSS from the autopilot"},
          {"vehicle.px4_origin_shift_east_m", "vehicle.gnss_source", {"autopilot"}, "GNSS from the autopilot"},
          {"vehicle.px4_origin_shift_north_m", "vehicle.gnss_source", {"autopilot"}, "GNSS from the autopilot"},
          {"wind.direction_deg", "wind.mean_mps", {}, "a mean wind"},
          {"wind.turn_rate_dps", "wind.mean_mps", {}, "a mean wind"},
          {"imu.attitude_error_std_rad", "imu.source", {"accelerometer"}, "the accelerometer source"},
          {"imu.accel_bias_std_mps2", "imu.source", {"accelerometer"}, "the accelerometer source"},
          {"imu.accel_noise_std_mps2", "imu.source", {"accelerometer"}, "the accelerometer source"},
      });
  // The mission is the agents' (each holds the plan), written at the top of a scenario as in an agent's file.
  schema.aliases = {{"agent.k", "agent.formation.k"},
                    {"agent.circle_fit", "agent.formation.circle_fit"},
                    {"mission.legs", "agent.mission.legs"},
                    {"mission.start", "agent.mission.start"},
                    {"mission.start_s", "agent.mission.start_s"},
                    {"mission.max_speed_mps", "agent.mission.max_speed_mps"}};
  schema.derived = {{"agent.formation.radius_m", "formation.spacing_m"},
                    {"agent.sensor.fov_deg", "mps.fov_deg"},
                    {"agent.sensor.mount_deg", "mps.mount_deg"},
                    {"agent.focal.imu_source", "imu.source"},
                    {"agent.mission.response_s", "dynamics.velocity_lag_s"}};
  schema.foreign_sections = {"study"};
  return t;
}

const params::Table<Scenario>& table() {
  static const params::Table<Scenario> t = makeTable();
  return t;
}

}  // namespace

Scenario loadScenario(const std::string& path, const std::vector<std::string>& overrides) {
  return table().load(path, overrides);
}

Scenario parseScenario(const std::string& yaml_text, const std::string& source,
                       const std::vector<std::string>& overrides) {
  return table().parse(yaml_text, source, overrides);
}

Scenario parseRecordedScenario(const std::string& yaml_text, const std::string& source,
                               const std::vector<std::string>& overrides) {
  return table().parseDump(yaml_text, source, overrides);
}

std::string scenarioToYaml(const Scenario& scenario) { return table().dump(scenario); }

std::string describeScenarioParameters() { return table().describe(); }

std::string canonicalScenarioKey(const std::string& key) {
  for (const params::Alias& a : table().schema().aliases) {
    if (a.alias == key) return a.key;
  }
  return key;
}

}  // namespace swa::sim

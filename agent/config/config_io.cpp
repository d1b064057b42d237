#include "swa/agent/config_io.h"

#include <cmath>
#include <iterator>
#include <limits>

namespace swa::agent {

namespace {

using params::closed;
using params::open;
using params::openClosed;

template <class Enum, std::size_t N>
std::vector<std::pair<Enum, std::string>> named(const std::pair<Enum, const char*> (&names)[N]) {
  return {std::begin(names), std::end(names)};
}

constexpr double kMaxMissionSpeed_mps = 50.0;
constexpr double kMaxMissionDistance_m = 1e6;
constexpr double kMaxMissionTime_s = 1e6;

// mission.legs: a list of legs, each a velocity over a time or a point at a speed (mission.h).
params::Spec legsSpec() {
  params::Spec s = params::makeSpec("mission.legs", params::Kind::kRecordList, "");
  s.meaning =
      "the swarm's plan, the same for every agent: legs flown one after the other from mission.start, then "
      "a hold; a velocity over a time, or a point (relative to where the swarm was at the start) at a speed";
  params::Spec velocity = params::makeSpec("velocity_mps", params::Kind::kReal, "m/s",
                                           params::closed(-kMaxMissionSpeed_mps, kMaxMissionSpeed_mps));
  velocity.components = 2;
  params::Spec to =
      params::makeSpec("to_m", params::Kind::kReal, "m", params::closed(-kMaxMissionDistance_m, kMaxMissionDistance_m));
  to.components = 2;
  s.fields = {velocity, params::makeSpec("duration_s", params::Kind::kReal, "s", openClosed(0, kMaxMissionTime_s)), to,
              params::makeSpec("speed_mps", params::Kind::kReal, "m/s", openClosed(0, kMaxMissionSpeed_mps))};
  s.forms = {{"velocity_mps", "duration_s"}, {"to_m", "speed_mps"}};
  s.example = "{velocity_mps: [-4, 0], duration_s: 125}";
  s.expected = "a list of legs such as [{velocity_mps: [3, 0], duration_s: 10}, {to_m: [0, 0], speed_mps: 4}] or []";
  s.range_text = "list of {velocity_mps: [east, north], duration_s} or {to_m: [east, north], speed_mps}";
  s.comment = "legs {velocity_mps: [east, north], duration_s} or {to_m: [east, north], speed_mps}; [] = hold";
  s.type_name = "leg list";
  return s;
}

// The records as legs: a velocity leg as it is, a point leg from the end of the legs before it.
std::vector<MissionLeg> legsOf(const std::vector<params::Record>& records) {
  std::vector<MissionLeg> legs;
  for (const params::Record& r : records) {
    if (!std::isnan(r[0])) {
      legs.push_back({Vec2(r[0], r[1]), r[2]});
    } else {
      appendLegTo(legs, Vec2(r[3], r[4]), r[5]);
    }
  }
  return legs;
}

// Every tunable of AgentConfig, declared here exactly once.
params::Table<AgentConfig> makeTable() {
  params::Table<AgentConfig> t("SWA agent configuration", "configuration", "formation:", "formation.radius_m=12");
  SWA_PARAM(t, choice, mode, named(kModeNames),
            "swa = relative formation; standalone = dead-reckoning baseline; anchored = swa + GNSS hold");

  SWA_PARAM(t, number, surroundings.q_pos_m2, "m^2", openClosed(0, 100),
            "Q_o position block, per q_ref_dt_s of track prediction");
  SWA_PARAM(t, number, surroundings.q_vel_m2ps2, "m^2/s^2", openClosed(0, 100),
            "Q_o velocity block, per q_ref_dt_s of track prediction");
  SWA_PARAM(t, number, surroundings.q_acc_m2ps4, "m^2/s^4", openClosed(0, 1000),
            "Q_o acceleration block, per q_ref_dt_s of track prediction");
  SWA_PARAM(t, number, surroundings.q_ref_dt_s, "s", openClosed(0, 1),
            "prediction step the Q_o blocks refer to (scaled linearly with the actual step)");
  SWA_PARAM(t, number, surroundings.r_det_m2, "m^2", openClosed(0, 100),
            "R_o: detection noise used when a detection carries no covariance of its own");
  SWA_PARAM(t, number, surroundings.init_vel_var_m2ps2, "m^2/s^2", openClosed(0, 100),
            "velocity variance of a new track");
  SWA_PARAM(t, number, surroundings.init_acc_var_m2ps4, "m^2/s^4", openClosed(0, 1000),
            "acceleration variance of a new track");
  SWA_PARAM(t, number, surroundings.confirm_hits, "", closed(1, 20),
            "detections (M) before a track may be used as a neighbour");
  SWA_PARAM(t, number, surroundings.track_timeout_s, "s", openClosed(0, 60),
            "a confirmed track is removed after this long without a detection");
  SWA_PARAM(t, number, surroundings.tentative_timeout_s, "s", openClosed(0, 60),
            "a tentative track is removed after this long without a detection");
  SWA_PARAM(t, number, surroundings.gate_probability, "", open(0, 1),
            "chi-square gate probability (2 dof) for anonymous association");

  SWA_PARAM(t, number, formation.radius_m, "m", openClosed(0, 1000),
            "r: desired distance to the neighbours (radius of the fitted circle)");
  SWA_PARAM(t, choice, formation.neighbourhood, named(kNeighbourhoodRuleNames),
            "gabriel = tracks with no other track inside the circle on the segment to them as diameter; "
            "k_nearest = the k nearest tracks");
  SWA_PARAM(t, number, formation.k, "", closed(1, 16),
            "k_nearest only: number of nearest neighbours used for the floating frame");
  SWA_PARAM(t, number, formation.sensing_range_m, "m", openClosed(0, 10000),
            "tracks farther than this are not neighbours");
  SWA_PARAM(t, number, formation.max_edge_factor, "", closed(1, 100),
            "gabriel only: neighbours other than the nearest must be closer than this times r");
  SWA_PARAM(t, choice, formation.circle_fit, named(kCircleFitNames),
            "fit for n >= 3 neighbours; algebraic = the paper's Kasa fit (collapses, k = 3)");
  SWA_PARAM(t, number, formation.far_neighbour_weight, "", openClosed(0, 1),
            "fixed_radius fit: weight of the neighbours beyond the two nearest (which weigh 1)");

  SWA_PARAM(t, number, focal.tau_s, "s", openClosed(0, 60),
            "tau: time constant of the velocity damping exp(-dt/tau) of the focal UAV model");
  SWA_PARAM(t, number, focal.q_pos_m2, "m^2", openClosed(0, 100), "Q_f position block, per q_ref_dt_s, before q_scale");
  SWA_PARAM(t, number, focal.q_vel_m2ps2, "m^2/s^2", openClosed(0, 100),
            "Q_f velocity block, per q_ref_dt_s, before q_scale");
  SWA_PARAM(t, number, focal.q_acc_m2ps4, "m^2/s^4", openClosed(0, 1000),
            "Q_f acceleration block, per q_ref_dt_s, before q_scale");
  SWA_PARAM(t, number, focal.q_scale, "", openClosed(0, 100), "factor applied to all of Q_f (1 = Table I)");
  SWA_PARAM(t, number, focal.q_ref_dt_s, "s", openClosed(0, 1),
            "prediction step the Q_f blocks refer to (scaled linearly with the actual step)");
  SWA_PARAM(t, number, focal.fit_noise_gain, "", closed(0, 100),
            "R_c = this x the frame fit's covariance propagated from the neighbours' tracks (0 = constant r_pos_m2)");
  SWA_PARAM(t, number, focal.r_pos_m2, "m^2", openClosed(0, 100),
            "R_c where the fit has no covariance model (algebraic fit, coincident points) or fit_noise_gain = 0");
  SWA_PARAM(t, number, focal.r_acc_m2ps4, "m^2/s^4", openClosed(0, 1000),
            "R_a: noise of the tilt-derived acceleration measurement");
  SWA_PARAM(t, number, focal.q_c_mps2, "m/s^2/rad", openClosed(0, 50), "q_c: lateral acceleration per radian of tilt");
  SWA_PARAM(t, choice, focal.imu_source, named(kImuSourceNames),
            "the acceleration the focal filter fuses: tilt (q_c x the attitude: the thrust's push only, the paper's) "
            "or accelerometer (the specific force turned by the attitude, gravity removed: every push, drag and "
            "wind included; a sample without one is read from the tilt, logged and counted)");
  SWA_PARAM(t, number, focal.frame_timeout_s, "s", openClosed(0, 600),
            "without a floating frame for this long, dead reckoning is no longer trusted");
  SWA_PARAM(t, number, focal.bias_window_s, "s", closed(0, 3600),
            "IMU-bias removal: window of the running mean subtracted from the tilt acceleration (0 = off); "
            "assumes a hovering UAV's acceleration averages to zero");
  SWA_PARAM(t, number, focal.bias_freeze_speed_mps, "m/s", openClosed(0, 50),
            "the IMU-bias mean is frozen while the commanded speed exceeds this");
  SWA_PARAM(t, number, focal.bias_freeze_hold_s, "s", closed(0, 600),
            "the IMU-bias mean stays frozen this long after the commanded speed last exceeded "
            "bias_freeze_speed_mps");

  SWA_PARAM(t, number, control.k_p, "1/s", closed(0, 20), "position feedback gain");
  SWA_PARAM(t, number, control.k_v, "", closed(0, 10), "velocity feedback gain");
  SWA_PARAM(t, number, control.v_max_mps, "m/s", openClosed(0, 50), "saturation of the desired velocity |v_d|");
  SWA_PARAM(t, number, control.k_yaw, "1/s", closed(0, 20),
            "heading gain (sensor.fov_deg < 360 only): yaw rate per radian of heading error");
  SWA_PARAM(t, number, control.max_yaw_rate_radps, "rad/s", openClosed(0, 10),
            "saturation of the commanded yaw rate: the vehicle's limit");
  SWA_PARAM(t, number, control.facing_deg, "deg", closed(-360, 360),
            "world direction (counter-clockwise from east) every sensor axis holds when sensor.fov_deg < 360");
  SWA_PARAM(t, number, sensor.fov_deg, "deg", openClosed(0, 360),
            "the relative sensor's horizontal field of view (360 = all round: the heading is never commanded)");
  SWA_PARAM(t, number, sensor.mount_deg, "deg", closed(-360, 360),
            "the centre of that field of view, counter-clockwise from body x");
  SWA_PARAM(t, choice, sensor.input, named(kDetectionInputNames),
            "the detections' message: swa (swa/uav<I>/detections), vision_msgs (vision_msgs/Detection3DArray on "
            "/uav<I>/detections) or uvdar (mrs_msgs/PoseWithCovarianceArrayStamped on /uav<I>/uvdar/measuredPoses), "
            "in the frame uav<I>/fcu or base_link (x forward, y left), or sensor.detector_frame; swa_sim publishes the "
            "one chosen");
  SWA_PARAM(t, text, sensor.detector_frame,
            "a real detector's own frame id, placed on the body by the three keys below ('' = the detector publishes "
            "in the body frame)",
            "a frame id of letters, digits and _ . / - (or '')");
  SWA_PARAM(t, number, sensor.detector_yaw_deg, "deg", closed(-360, 360),
            "sensor.detector_frame's x axis in the body, counter-clockwise from body x");
  SWA_PARAM(t, number, sensor.detector_x_m, "m", closed(-10, 10), "sensor.detector_frame's origin, body x (forward)");
  SWA_PARAM(t, number, sensor.detector_y_m, "m", closed(-10, 10), "sensor.detector_frame's origin, body y (left)");
  SWA_PARAM(t, text, sensor.detector_classes,
            "vision_msgs only: the class ids (of each detection's best hypothesis) taken for UAVs, comma-separated; "
            "others are dropped and counted ('' = every detection)",
            "class ids separated by commas, e.g. uav,drone (or '')");

  SWA_PARAM(t, number, anchor.gain, "", closed(0, 10),
            "weight of the absolute (GNSS) hold added to the relative command in anchored mode");
  SWA_PARAM(t, number, anchor.gnss_min_std_m, "m", openClosed(0, 100),
            "floor for the standard deviation a GNSS fix claims");
  SWA_PARAM(t, number, anchor.regain_ramp_s, "s", closed(0, 600),
            "anchored mode: when GNSS returns after an outage, the GNSS hold is blended in linearly over this time, "
            "so that its return is no step in the command (0: at once)");

  SWA_PARAM(t, number, limits.max_detections, "", closed(1, 1024),
            "a detection set larger than this is rejected whole");
  SWA_PARAM(t, number, limits.max_target_id, "", closed(1, static_cast<double>(std::numeric_limits<int>::max())),
            "detections with a target ID above this are treated as corrupt");
  SWA_PARAM(t, number, limits.max_tilt_rad, "rad", openClosed(0, 1.5),
            "|roll|, |pitch| beyond this are not treated as lateral flight");
  SWA_PARAM(t, number, limits.max_abs_position_m, "m", openClosed(0, 1e9),
            "detections and GNSS fixes farther than this are corrupt");
  SWA_PARAM(t, number, limits.max_abs_heading_rad, "rad", openClosed(0, 1e3),
            "IMU headings beyond +- this are corrupt");
  SWA_PARAM(t, number, limits.max_stamp_jump_s, "s", openClosed(0, 3600),
            "a sample stamped more than this after the previous one of its stream (or this far from the IMU's "
            "clock) is not trusted");
  SWA_PARAM(t, number, limits.resync_samples, "", closed(2, 100),
            "consecutive samples of a consistent new timeline after which a stream re-synchronises to it");
  t.add(
      legsSpec(),
      [](const AgentConfig& c) {
        std::vector<params::Record> out;
        const double absent = std::numeric_limits<double>::quiet_NaN();
        for (const MissionLeg& l : c.mission.legs) {
          out.push_back({l.velocity_mps.x(), l.velocity_mps.y(), l.duration_s, absent, absent, absent});
        }
        return params::Value(out);
      },
      [](AgentConfig& c, const params::Value& v) {
        c.mission.legs = legsOf(std::get<std::vector<params::Record>>(v));
      });
  SWA_PARAM(t, choice, mission.start, named(kMissionStartNames),
            "when the first leg begins: gnss_loss (the first GNSS sample without a fix) or time (mission.start_s)");
  SWA_PARAM(t, number, mission.start_s, "s", closed(0, kMaxMissionTime_s),
            "mission.start time: the first leg begins at this stamp of the IMU's clock");
  SWA_PARAM(t, number, mission.response_s, "s", closed(0, 60),
            "the vehicle's velocity response (first-order time constant): the swarm's frame follows each leg's "
            "velocity through it; 0: at once");
  SWA_PARAM(t, number, mission.max_speed_mps, "m/s", openClosed(0, kMaxMissionSpeed_mps),
            "a plan with a faster leg is refused (the vehicles' cruise limit)");
  // Keys a chosen mode ignores: giving one is an error (a user who sets a key that changes nothing should know).
  // The standalone baseline flies on dead reckoning alone and fits no floating frame; the radius stays, as the
  // monitor scores every run against it. The mode comes first: it is what a message should name.
  std::vector<params::Applies>& applies = t.schema().applies;
  for (const params::Spec& s : t.schema().specs) {
    if (s.key.rfind("formation.", 0) == 0 && s.key != "formation.radius_m") {
      applies.push_back({s.key, "mode", {"swa", "anchored"}, "the modes that fly in formation"});
    }
  }
  applies.insert(
      applies.end(),
      {
          {"formation.k", "formation.neighbourhood", {"k_nearest"}, "the k_nearest rule"},
          {"formation.max_edge_factor", "formation.neighbourhood", {"gabriel"}, "the gabriel rule"},
          {"formation.far_neighbour_weight", "formation.circle_fit", {"fixed_radius"}, "the fixed_radius fit"},
          {"anchor.gain", "mode", {"anchored"}, "anchored mode"},
          {"anchor.regain_ramp_s", "mode", {"anchored"}, "anchored mode"},
          {"anchor.gnss_min_std_m", "mode", {"standalone", "anchored"}, "the modes that use GNSS"},
          {"focal.bias_freeze_speed_mps", "focal.bias_window_s", {}, "IMU-bias removal"},
          {"focal.bias_freeze_hold_s", "focal.bias_window_s", {}, "IMU-bias removal"},
          {"sensor.detector_frame", "sensor.input", {"vision_msgs", "uvdar"}, "a real detector's messages"},
          {"sensor.detector_yaw_deg", "sensor.detector_frame", {}, "a detector in its own frame"},
          {"sensor.detector_x_m", "sensor.detector_frame", {}, "a detector in its own frame"},
          {"sensor.detector_y_m", "sensor.detector_frame", {}, "a detector in its own frame"},
          {"sensor.detector_classes", "sensor.input", {"vision_msgs"}, "vision_msgs detections"},
          {"mission.start_s", "mission.start", {"time"}, "a mission started at a time"},
      });
  t.schema().checks = configChecks("");
  t.schema().relations = {
      {"surroundings.tentative_timeout_s", false, "surroundings.track_timeout_s",
       "a tentative track must not outlive a confirmed one"},
      {"formation.radius_m", true, "formation.sensing_range_m",
       "neighbours sit about r apart, so they must be within sensing range"},
      {"formation.sensing_range_m", false, "limits.max_abs_position_m",
       "otherwise detections within sensing range are rejected as corrupt"},
  };
  return t;
}

}  // namespace

std::vector<params::Check> configChecks(const std::string& prefix) {
  const std::string legs_key = prefix + "mission.legs";
  const std::string max_key = prefix + "mission.max_speed_mps";
  return {{{legs_key, max_key}, [legs_key, max_key](const params::Values& v, std::vector<std::string>& problems) {
             const double max_speed = params::number(v, max_key);
             std::vector<MissionLeg> legs;
             const std::vector<params::Record>& records = params::records(v, legs_key);
             for (std::size_t i = 0; i < records.size(); ++i) {
               const params::Record& r = records[i];
               const std::string name = legs_key + "[" + std::to_string(i) + "]";
               const bool velocity_form = !std::isnan(r[0]);
               const double speed = velocity_form ? Vec2(r[0], r[1]).norm() : r[5];
               if (speed > max_speed) {
                 problems.push_back(name + " flies at " + params::formatYamlNumber(speed) + " m/s, above " + max_key +
                                    " = " + params::formatYamlNumber(max_speed) + " m/s");
               }
               const std::size_t before = legs.size();
               if (velocity_form) {
                 legs.push_back({Vec2(r[0], r[1]), r[2]});
               } else if (appendLegTo(legs, Vec2(r[3], r[4]), r[5]) && legs.size() == before) {
                 problems.push_back(
                     name + " goes to [" + params::formatYamlNumber(r[3]) + ", " + params::formatYamlNumber(r[4]) +
                     "], where the plan already is: a leg that goes nowhere (the hold follows the last)");
               }
             }
           }}};
}

const params::Table<AgentConfig>& configTable() {
  static const params::Table<AgentConfig> table = makeTable();
  return table;
}

AgentConfig loadAgentConfig(const std::string& yaml_path) { return configTable().load(yaml_path); }

AgentConfig parseAgentConfig(const std::string& yaml_text, const std::string& source_name) {
  return configTable().parse(yaml_text, source_name);
}

void applyOverride(AgentConfig& config, const std::string& dotted_key, const std::string& value) {
  config = configTable().override(config, {dotted_key + "=" + value});
}

AgentConfig applyOverrides(AgentConfig config, const std::vector<std::string>& key_eq_value) {
  return configTable().override(config, key_eq_value);
}

void validateAgentConfig(const AgentConfig& config, const std::string& source_name) {
  configTable().validate(config, source_name);
}

std::string describeParameters() { return configTable().describe(); }

std::string toYaml(const AgentConfig& config) { return configTable().dump(config); }

}  // namespace swa::agent

#pragma once
// Every tunable of the agent in one typed struct. Defaults are the paper's Table I and DESIGN.md §3;
// where a default deliberately differs from the paper, the comment says why.

#include <cstddef>
#include <string>
#include <utility>

#include "swa/agent/mission.h"

namespace swa::agent {

enum class Mode { kSwa, kStandalone, kAnchored };
enum class CircleFit { kFixedRadius, kAlgebraic };
enum class NeighbourhoodRule { kGabriel, kKNearest };
// Where the agent reads its relative detections: SWA's own Detections on swa/uav<I>/detections, a ROS 2
// vision_msgs/Detection3DArray on /uav<I>/detections, or UVDAR's mrs_msgs/PoseWithCovarianceArrayStamped on
// /uav<I>/uvdar/measuredPoses (detection_adapter.h converts the latter two).
enum class DetectionInput { kSwa, kVisionMsgs, kUvdar };

// The name of each value in files and messages, listed once: toString and the configuration's choices read these.
inline constexpr std::pair<Mode, const char*> kModeNames[] = {
    {Mode::kSwa, "swa"}, {Mode::kStandalone, "standalone"}, {Mode::kAnchored, "anchored"}};
inline constexpr std::pair<CircleFit, const char*> kCircleFitNames[] = {{CircleFit::kFixedRadius, "fixed_radius"},
                                                                        {CircleFit::kAlgebraic, "algebraic"}};
inline constexpr std::pair<NeighbourhoodRule, const char*> kNeighbourhoodRuleNames[] = {
    {NeighbourhoodRule::kGabriel, "gabriel"}, {NeighbourhoodRule::kKNearest, "k_nearest"}};
inline constexpr std::pair<DetectionInput, const char*> kDetectionInputNames[] = {
    {DetectionInput::kSwa, "swa"}, {DetectionInput::kVisionMsgs, "vision_msgs"}, {DetectionInput::kUvdar, "uvdar"}};

// Where the focal filter's acceleration comes from (issue #44): the attitude alone (the paper's q_c model, which
// sees the thrust only), or the accelerometer's specific force turned by the attitude (every force, drag included).
enum class ImuSource { kTilt, kAccelerometer };
inline constexpr std::pair<ImuSource, const char*> kImuSourceNames[] = {{ImuSource::kTilt, "tilt"},
                                                                        {ImuSource::kAccelerometer, "accelerometer"}};

struct SurroundingsConfig {
  // Q_o diagonal blocks, per `q_ref_dt_s` of prediction (scaled linearly with the actual step).
  double q_pos_m2 = 1e-3;
  double q_vel_m2ps2 = 1e-2;
  double q_acc_m2ps4 = 1e-1;
  double q_ref_dt_s = 0.01;         // Table I values are per 100 Hz step
  double r_det_m2 = 0.1;            // R_o, used when a detection carries no covariance of its own
  double init_vel_var_m2ps2 = 1.0;  // a new track's velocity prior: neighbours hover or move slowly
  double init_acc_var_m2ps4 = 0.5;
  int confirm_hits = 3;               // M hits before a track may be used as a neighbour
  double track_timeout_s = 1.0;       // confirmed track removed after this long without a detection
  double tentative_timeout_s = 0.25;  // tentative track removed after this long (2.5 MPS periods at 10 Hz)
  double gate_probability = 0.99;     // chi-square gate (2 dof) for anonymous association
};

struct FormationConfig {
  double radius_m = 10.0;  // r
  // Gabriel (DESIGN §3.2): in a triangular lattice it selects exactly the lattice edges, so every distance can be r
  // at once. k nearest with k = 3 squeezes the formation to ~0.93 r (a second-shell UAV at sqrt(3) r is pulled to r);
  // k = 2 keeps the spacing but lets the swarm split.
  NeighbourhoodRule neighbourhood = NeighbourhoodRule::kGabriel;
  int k = 3;                      // k_nearest only: neighbours used for the floating frame
  double sensing_range_m = 40.0;  // tracks farther than this are not neighbours
  // Gabriel only: a neighbour other than the nearest must be closer than this times r. A UAV hidden by the field of
  // view or a lost track stops blocking the edge to the second-shell UAV behind it (sqrt(3) r or 2 r away); without
  // the cap that UAV would be pulled to r. 1.3 rather than 1.5: on a swarm's ragged rim Gabriel also keeps edges of
  // 1.3-1.5 r that are no lattice edge, and pulling them to r squeezed the whole formation by about 3 % at N = 64 and
  // with a 240 deg field of view (issue #26, BENCHMARKS.md); no size or field of view measured split with 1.3.
  double max_edge_factor = 1.3;
  CircleFit circle_fit = CircleFit::kFixedRadius;  // the paper's algebraic fit collapses with k = 3 (DESIGN §3)
  // Fixed-radius fit: weight of every neighbour beyond the two nearest (they weigh 1). With 3-6 equidistant
  // neighbours the unweighted fit reads d_NB ~4 % short (DESIGN §3.3); 1 = unweighted.
  double far_neighbour_weight = 0.2;
};

struct FocalConfig {
  double tau_s = 2.8;
  // Q_f per `q_ref_dt_s`, scaled by `q_scale`. Table I gives diag(5e-2, 5e-1, 5) and R_c = 0.02; with those the
  // filter is badly conservative (velocity ANEES ~0.02 for n_x = 2 in the §IV-C scenario). The defaults are tuned
  // against the simulator model of DESIGN §4 by two ANEES Monte Carlos that must both hold: the single agent of
  // tests/unit/test_focal_consistency.cpp and the closed loop of the default scenario
  // (tests/closedloop/test_cohesion.cpp; tuned on seeds 101-120, asserted on 1-10).
  double q_pos_m2 = 1.5e-4;
  double q_vel_m2ps2 = 1.7e-4;
  double q_acc_m2ps4 = 0.1;
  double q_scale = 1.0;
  double q_ref_dt_s = 0.01;
  // R_c of the floating-frame position measurement is the frame fit's own covariance, propagated from the
  // neighbours' track covariances through the fit's geometry (frame_fit.h: fitCovariance), times this gain. The
  // gain stands for what the propagation leaves out, above all that a track's error is correlated from scan to
  // scan (a track filter with P ~ 0.06 against R_o = 0.1 keeps ~60 % of its error to the next scan) while the
  // focal filter fuses the fits as if they were independent. A constant R_c cannot be consistent: the fit through
  // two neighbours is known about twice as poorly as through six, and large swarms have more UAVs with six, so
  // with the constant 0.1 the position ANEES rose from 2.2 at N = 8 to 2.4 at 64 with 63 % of steps in band.
  // Measured by the closed-loop ANEES at N = 8 ... 64 (BENCHMARKS.md); 0 = the constant r_pos_m2 below.
  double fit_noise_gain = 3.0;
  // R_c (Table I: 0.02) where the fit has no covariance model (the algebraic fit, coincident points) or with
  // fit_noise_gain = 0. The frame fit on bank-smoothed tracks is noisier and its error is correlated in time;
  // with 0.03 the closed-loop position ANEES was 4.6 (Gabriel) with 40 % of steps in the chi-square band.
  double r_pos_m2 = 0.1;
  double r_acc_m2ps4 = 2.25;                         // R_a
  double q_c_mps2 = 6.35;                            // tilt (rad) -> lateral acceleration
  ImuSource imu_source = ImuSource::kAccelerometer;  // issue #44: holds better in gusts and wind (BENCHMARKS.md)
  double frame_timeout_s = 2.0;  // without a frame for this long the agent stops trusting dead reckoning
  // IMU-bias removal (DESIGN §3.4): the tilt-derived acceleration minus its running mean over this window. Assumes
  // a hovering UAV's true acceleration averages to zero over the window (its velocity stays bounded), so the mean is
  // the bias. 0 turns it off (the paper's filter).
  double bias_window_s = 30.0;
  // The mean is frozen while the command is faster than this, and for bias_freeze_hold_s after: a manoeuvring UAV's
  // acceleration is not zero-mean, least of all where it turns round at low speed.
  double bias_freeze_speed_mps = 0.5;
  double bias_freeze_hold_s = 5.0;
};

struct ControlConfig {
  // Table I: 0.5, tuned to the paper's vehicle. With the simulator's 1 s first-order velocity lag (DESIGN §4) 0.5
  // leaves the loop under-damped and each formation breathes by +-0.3 m; 0.7 damps it (zeta ~ 1): 38 of 40 seeds
  // of the default scenario within +-3 % of r at 120 s, against 31 of 40 (BENCHMARKS.md). --set control.k_p=0.5
  // restores the paper's gain.
  double k_p = 0.7;        // 1/s
  double k_v = 0.63;       // -
  double v_max_mps = 2.0;  // saturation of |v_d|
  // Heading control (issue #26), only with a sensor that does not see all round (sensor.fov_deg < 360): the agent
  // turns its sensor's axis to the world direction facing_deg (counter-clockwise from east) and holds it there,
  // yaw rate = k_yaw x heading error, saturated at max_yaw_rate_radps (the vehicle's limit). Every UAV facing the
  // same way means no pair is blind to each other: j lies in i's blind sector only if i lies in the opposite
  // sector of j, which a blind sector narrower than 180 deg never covers. No communication: the heading is the
  // agent's own (the stable frame is world-aligned, DESIGN §2).
  double k_yaw = 1.0;  // 1/s
  double max_yaw_rate_radps = 0.5;
  double facing_deg = 0.0;
};

// The relative sensor as the agent knows it. In a scenario both default to the simulator's mps.fov_deg and
// mps.mount_deg, as formation.radius_m defaults to the spacing.
struct SensorConfig {
  double fov_deg = 360.0;  // horizontal field of view; 360: all round, and the heading is never commanded
  double mount_deg = 0.0;  // the centre of the field of view, counter-clockwise from body x
  DetectionInput input = DetectionInput::kSwa;  // the message type (and topic) the detections come in; the simulator
                                                // publishes that one
  // A real detector (vision_msgs, uvdar) may publish in its own sensor frame: its frame id, and where that frame sits
  // on the body (x forward, y left; yaw counter-clockwise from body x). Empty: only the body frames are accepted.
  std::string detector_frame;
  double detector_yaw_deg = 0.0;
  double detector_x_m = 0.0, detector_y_m = 0.0;
  // vision_msgs' class ids taken for UAVs, comma-separated; empty: every detection. UVDAR's carry no class.
  std::string detector_classes;
};

struct AnchorConfig {
  // Weight of the absolute (GNSS) hold added to the relative command in `anchored` mode.
  double gain = 0.2;
  double gnss_min_std_m = 0.05;  // floor for the std a fix reports: a receiver claiming 1 mm is not believed
  // After GNSS returns, the hold is blended in linearly over this time: during the outage the swarm drifted off the
  // hold point, and switching the hold's pull back on at once is a step in the command (issue #43: 0.4-0.5 m/s in one
  // IMU period with 10 s of outage). 0: at once. The first fix of a flight is not a return (the hold starts there).
  double regain_ramp_s = 2.0;
};

struct LimitsConfig {
  std::size_t max_detections = 64;  // a larger detection set is rejected whole
  // IDs above this are treated as corrupt: the largest UAV id of the swarm (the simulator numbers 0..255 at most).
  // Every accepted id can become a track, so a generous bound lets a faulty sensor create phantom neighbours.
  int max_target_id = 255;
  // |roll|, |pitch| beyond 80 deg is not lateral flight. Not tighter: the tilt noise of R_a = 2.25 (0.24 rad std)
  // would otherwise reject ~0.1 % of genuine samples.
  double max_tilt_rad = 1.4;
  double max_abs_position_m = 1e6;                  // detections / fixes farther than this are corrupt
  double max_abs_heading_rad = 12.566370614359172;  // 4 pi: a heading is an angle, wrapped or not by much
  // Stamps (stream_clock.h): a sample more than this after the previous one of its stream (or, for detections and
  // GNSS, this far from the IMU's clock) is not trusted; this many consecutive samples of a consistent new timeline
  // re-synchronise the stream (a producer that restarted its clock), and the agent restarts its estimates.
  double max_stamp_jump_s = 1.0;
  int resync_samples = 4;
};

struct AgentConfig {
  Mode mode = Mode::kSwa;
  SurroundingsConfig surroundings;
  FormationConfig formation;
  FocalConfig focal;
  ControlConfig control;
  SensorConfig sensor;
  AnchorConfig anchor;
  LimitsConfig limits;
  MissionConfig mission;
};

std::string toString(Mode mode);
std::string toString(CircleFit fit);
std::string toString(NeighbourhoodRule rule);
std::string toString(DetectionInput input);
std::string toString(ImuSource source);
std::string toString(MissionStart start);

}  // namespace swa::agent

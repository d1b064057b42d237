#pragma once
// The agent facade: stamped IMU, detection and GNSS samples in; velocity commands and diagnostics out. One UAV,
// one instance. No clock reads, no threads, no globals: the same samples in the same order give bit-identical
// commands, which is what makes the closed-loop tests and the lockstep simulator reproducible.
//
// Ordering: each stream must have strictly increasing stamps (a repeated or older stamp is rejected and counted).
// Across streams, a sample older than the focal filter (e.g. detections with sensor latency) is applied at the
// filter's time; the error is neighbour velocity x latency, well below R_c for the 10-100 ms latencies of MPS.

#include <optional>
#include <vector>

#include "swa/agent/config.h"
#include "swa/agent/diagnostics.h"
#include "swa/agent/focal_estimator.h"
#include "swa/agent/imu_bias.h"
#include "swa/agent/mission.h"
#include "swa/agent/neighbourhood.h"
#include "swa/agent/samples.h"
#include "swa/agent/stream_clock.h"
#include "swa/agent/track_bank.h"

namespace swa::agent {

class Agent {
 public:
  explicit Agent(const AgentConfig& config);

  // Every IMU sample, accepted or not, is answered with a command (the 100 Hz control step). A rejected sample gets
  // the previous command again with `fresh` false: the command is always finite and within saturation. Stamps are
  // judged per stream (stream_clock.h): a restart of the IMU clock restarts the agent's estimates.
  VelocityCommand onImu(const ImuSample& imu);
  void onDetections(const DetectionSet& detections);
  void onGnss(const GnssSample& gnss);
  // A mission from the ground (mission.h), flown from the next accepted IMU sample on, from the point the plan has got
  // to (the mission starts there if it had not). A command that cannot be flown (missionCommandProblem, against
  // mission.max_speed_mps and limits.max_abs_position_m) is refused and counted and changes nothing: false. A second
  // command before that sample replaces the first.
  bool commandMission(const MissionCommand& command);

  const Diagnostics& diagnostics() const { return diag_; }
  const AgentConfig& config() const { return config_; }
  const TrackBank& bank() const { return bank_; }
  const FocalEstimator& focal() const { return focal_; }
  const FocalEstimator& absolute() const { return absolute_; }
  const ImuBiasRemover& imuBias() const { return imu_bias_; }

 private:
  bool acceptStamp(StreamClock& clock, StampNs stamp);
  void restartTimeline();
  void convertDetections(const DetectionSet& in);
  void updateFrame(StampNs stamp);
  Vec2 computeCommand(StampNs stamp);
  void refreshDiagnostics(StampNs stamp);
  FrameFit fit(const NeighbourPositions& neighbours) const;
  bool rankedFit() const;
  Mat2 fitNoise(const Neighbourhood& neighbours, const FrameFit& fit) const;
  void startMission(StampNs stamp);
  void takeCommand(StampNs stamp);
  void advanceMission(StampNs stamp);
  double missionTime(StampNs stamp) const;
  Vec2 relativeCommand() const { return command_ - plan_velocity_; }
  // The focal velocity against what the swarm is expected to fly (exactly the focal velocity without a mission).
  Vec2 relativeVelocity() const {
    return expected_velocity_ == plan_velocity_ ? focal_.velocity()
                                                : Vec2(focal_.velocity() - (expected_velocity_ - plan_velocity_));
  }
  Vec2 absoluteHold(StampNs stamp, const ControlConfig& cc) const;

  AgentConfig config_;
  TrackBank bank_;
  FocalEstimator focal_;     // floating frame (swa, anchored)
  FocalEstimator absolute_;  // take-off frame from GNSS + IMU (standalone, anchored)
  // Feeds focal_ only: the standalone baseline stays the paper's dead reckoning, so SWA is compared with it.
  ImuBiasRemover imu_bias_;
  Diagnostics diag_;

  Mat2 r_acc_;
  Mat2 r_pos_;
  double heading_rad_ = 0.0;
  bool have_heading_ = false;
  StreamClock imu_clock_, det_clock_, gnss_clock_;

  Neighbourhood neighbours_;
  bool frame_valid_ = false;
  StampNs last_frame_ns_ = 0;
  Vec2 frame_centre_ = Vec2::Zero();
  FitCase fit_case_ = FitCase::kNone;

  bool hold_point_set_ = false;
  Vec2 hold_point_ = Vec2::Zero();  // take-off position: the first valid GNSS fix
  StampNs last_valid_gnss_ns_ = 0;
  bool gnss_valid_ = false;
  // Anchored mode's hold: whether it pulled at the last command, whether it ever did, and since when it is blended in
  // again after an outage (anchor.regain_ramp_s).
  bool anchor_on_ = false;
  bool anchor_ever_on_ = false;
  std::optional<StampNs> anchor_ramp_from_ns_;

  // The mission (mission.h). The focal filter works in a frame that moves with the plan: its velocity is the UAV's
  // minus plan_velocity_, the plan's velocity at the last IMU step (the frame's), and its input the command minus it.
  // expected_velocity_ is what the swarm flies meanwhile (the plan through mission.response_s), against which the
  // formation law damps. The absolute filter stays in the take-off frame and follows the plan's path from
  // mission_origin_, its position at the start.
  MissionPlan plan_;
  std::optional<StampNs> mission_start_ns_;
  Vec2 plan_velocity_ = Vec2::Zero();
  Vec2 expected_velocity_ = Vec2::Zero();
  StampNs expected_at_ns_ = 0;
  Vec2 mission_origin_ = Vec2::Zero();
  std::optional<MissionCommand> pending_command_;

  Vec2 command_ = Vec2::Zero();
  double yaw_rate_ = 0.0;
  std::uint64_t seq_ = 0;
  std::vector<StableDetection> stable_;  // reused conversion buffer
};

}  // namespace swa::agent

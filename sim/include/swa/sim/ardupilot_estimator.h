#pragma once
// ArduPilot Copter's EKF3 as far as its horizontal position and the EKF failsafe go (Copter 4.5 to 4.6 and master
// alike), for the ArduPilot stand-in: whether the vehicle has a position (Copter::position_ok), given when GPS gave a
// fix and what external odometry arrived on ap/tf. Pure: no DDS, time is the simulation time, which is also the
// vehicle's own clock (its boot time).
//
// What is modelled (libraries/AP_NavEKF3/AP_NavEKF3_Control.cpp setAidingMode, ArduCopter/ekf_check.cpp,
// libraries/AP_DDS/AP_DDS_External_Odom.cpp, libraries/AP_VisualOdom; defaults from AP_NavEKF3.h, ArduCopter/config.h):
//   - horizontal position stays valid while a position measurement was fused within posRetryTimeNoVel_ms = 7 s (GPS,
//     or external navigation when the active source set takes it: EK3_SRCn_POSXY = 6); after that it is lost;
//   - ArduPilot's DDS odometry is a position (no velocity path exists in AP_DDS); its header stamp is taken as the
//     vehicle's boot time in ms without any offset: a stamp not after the vehicle's own time is fused at once, a later
//     one waits in the EKF's buffer (here: is not fused), so a bridge must stamp with the vehicle's clock;
//   - the EKF failsafe follows 1 s (ten failing 10 Hz checks) after the position is lost; it clears when the position
//     is back.
// The source switch itself (EK3_SRC1_* = GPS, EK3_SRC2_* = external navigation, switched by RC function 90 or the
// source-switching Lua script when GPS is lost) is summed up in one setting: whether external navigation is used
// once GPS is lost. Not modelled: variances and FS_EKF_THRESH, the EKF origin (it is set while GPS is good).

#include <optional>

#include "swa/agent/samples.h"

namespace swa::sim {

struct ArdupilotEstimatorParams {
  // Whether external navigation takes over once GPS is lost (the pre-flight setup of deploy/README.md: source set 2
  // with EK3_SRC2_POSXY = 6 and VISO_TYPE = 1, selected by the source-switching script). ArduPilot's own default is no
  // (EK3_SRC2_POSXY = 0, VISO_TYPE = 0).
  bool external_nav = true;
};

class ArdupilotEstimator {
 public:
  explicit ArdupilotEstimator(const ArdupilotEstimatorParams& params);

  // Whether the vehicle's GPS gives a fix at `now` (called every step).
  void gps(agent::StampNs now, bool fix);
  // An ap/tf odometry transform arriving at `now`, stamped `stamp_ns` (the header's stamp). False: not fused (not
  // taken while GPS is good, or external navigation off, or stamped after the vehicle's time).
  bool externalOdometry(agent::StampNs now, agent::StampNs stamp_ns);
  void update(agent::StampNs now);

  bool positionOk() const { return position_ok_; }
  bool ekfFailsafe() const { return ekf_failsafe_; }
  bool externalNavInUse() const { return using_external_nav_; }

 private:
  ArdupilotEstimatorParams params_;
  bool gps_fix_ = false;
  std::optional<agent::StampNs> last_position_ns_;  // the last fused position measurement, GPS or external
  std::optional<agent::StampNs> lost_since_ns_;
  bool position_ok_ = false;
  bool ekf_failsafe_ = false;
  bool using_external_nav_ = false;
};

}  // namespace swa::sim

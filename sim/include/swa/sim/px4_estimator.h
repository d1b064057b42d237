#pragma once
// PX4's EKF2 as far as its horizontal validity goes (v1.15 to v1.17 alike), for the PX4 stand-in: whether
// vehicle_local_position says xy_valid / v_xy_valid, given when GNSS was fused and what external vision arrived. Pure:
// no DDS, time is the simulation time.
//
// What is modelled (src/modules/ekf2/EKF/ekf_helper.cpp updateHorizontalDeadReckoningstatus, EKF2.cpp
// PublishLocalPosition, aid_sources/external_vision/ev_control.cpp; defaults from module.yaml and
// params_external_vision.yaml of each release):
//   - the filter is "aided" while GNSS was fused within 1 s (no_aid_timeout_max), or while external vision is in
//     use; while aided, the dead-reckoning timer is now - 1 s;
//   - external vision starts once two samples in a row came less than 200 ms apart (EV_MAX_INTERVAL) and stops after
//     400 ms without one (2 x EV_MAX_INTERVAL); a sample counts only for what EKF2_EV_CTRL fuses: bit 0 horizontal
//     position, bit 2 velocity;
//   - xy_valid and v_xy_valid (one getter in EKF2, so always together) turn false once the timer is EKF2_NOAID_TOUT
//     old: 5 s after the last GNSS fix, 4.4 s after the last external vision sample; they turn true again at once when
//     aiding returns;
//   - dead_reckoning is true while not aided.
// Not modelled: the delayed time horizon (EKF2_DELAY_MAX), the velocity accuracy test of the commander
// (COM_VEL_FS_EVH), fake position fusion, and whether the fused data is any good.

#include <optional>

#include "swa/agent/samples.h"

namespace swa::sim {

struct Px4EstimatorParams {
  double noaid_tout_s = 5.0;  // EKF2_NOAID_TOUT (5 000 000 us in v1.15 to v1.17)
  // EKF2_EV_CTRL: bit 0 horizontal position, 1 vertical position, 2 velocity, 3 yaw. PX4's own default is 15 in
  // v1.15 and 0 from v1.16; what the pre-flight table asks for (deploy/README.md) is 5, horizontal position and
  // velocity.
  int ev_ctrl = 5;
};

class Px4Estimator {
 public:
  explicit Px4Estimator(const Px4EstimatorParams& params);

  // Whether the vehicle's GNSS gives a fix at `now` (called every step).
  void gnss(agent::StampNs now, bool fix);
  // A vehicle_visual_odometry sample arriving at `now`, with a usable position and / or velocity (finite, in a frame
  // EKF2 takes).
  void externalVision(agent::StampNs now, bool position, bool velocity);
  // The filter's state at `now`, after the samples above.
  void update(agent::StampNs now);

  bool xyValid() const { return xy_valid_; }  // and v_xy_valid: the same getter in EKF2
  bool deadReckoning() const { return !aided_; }
  bool visionInUse() const { return ev_active_; }
  bool visionFusable(bool position, bool velocity) const;

 private:
  Px4EstimatorParams params_;
  std::optional<agent::StampNs> last_gnss_ns_;
  std::optional<agent::StampNs> last_ev_ns_;  // the newest sample EKF2_EV_CTRL lets count
  bool ev_active_ = false;
  bool aided_ = false;
  std::optional<agent::StampNs> aided_timer_ns_;  // now - 1 s while aided
  bool xy_valid_ = false;
};

}  // namespace swa::sim

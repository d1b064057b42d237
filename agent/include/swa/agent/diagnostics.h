#pragma once
// What the agent reports about itself: enough for the monitor to compute NEES against truth and for an operator to
// see why a UAV is not holding formation.

#include <array>
#include <cstdint>

#include "swa/agent/config.h"
#include "swa/agent/frame_fit.h"
#include "swa/agent/samples.h"

namespace swa::agent {

enum class Stage : std::uint8_t {
  kInitializing,  // no position reference yet: hovering
  kTracking,      // estimate referenced to the floating frame (or GNSS / take-off point in standalone)
  kLost           // reference lost for longer than focal.frame_timeout_s: hovering
};

// Inputs dropped, by reason. Every rejected sample or detection increments exactly one counter.
struct RejectCounters {
  std::uint64_t nonfinite = 0;     // NaN / inf in a value
  std::uint64_t out_of_order = 0;  // stamp not after the previous sample of the same stream
  std::uint64_t oversize = 0;      // detection set larger than limits.max_detections
  std::uint64_t bad_id = 0;        // target id neither anonymous nor in [0, limits.max_target_id]
  std::uint64_t implausible = 0;   // finite but physically impossible (tilt, distance, covariance, GNSS std)
  std::uint64_t no_heading = 0;    // detections before the first IMU sample: no way to rotate them
  std::uint64_t future = 0;        // stamp more than limits.max_stamp_jump_s ahead of its stream or the IMU clock
  std::uint64_t total() const {
    return nonfinite + out_of_order + oversize + bad_id + implausible + no_heading + future;
  }
};

struct Diagnostics {
  StampNs stamp_ns = 0;
  Mode mode = Mode::kSwa;
  Stage stage = Stage::kInitializing;
  Vec2 position_m = Vec2::Zero();  // focal estimate in its frame (floating frame; take-off frame in standalone)
  Vec2 velocity_mps = Vec2::Zero();
  Mat2 position_cov_m2 = Mat2::Zero();
  Mat2 velocity_cov_m2ps2 = Mat2::Zero();
  bool frame_valid = false;
  Vec2 frame_centre_m = Vec2::Zero();  // r_c, stable frame, relative to self
  FitCase fit_case = FitCase::kNone;
  int neighbour_count = 0;
  std::array<int, kMaxNeighbours> neighbour_ids{};
  int confirmed_tracks = 0;
  int tentative_tracks = 0;
  RejectCounters rejected;
  std::uint64_t commands = 0;
  std::uint64_t frame_shifts = 0;  // neighbour set changed; estimate shifted to the new frame
  std::uint64_t frame_resets = 0;  // neighbour set changed and the old frame was gone; position re-initialised
  std::uint64_t stamp_resyncs =
      0;  // an input stream's clock restarted (stream_clock.h); for the IMU the agent restarted
  // IMU samples without the accelerometer the agent fuses (focal.imu_source), read from the tilt instead: a vehicle
  // whose accelerometer stream started later than its attitude, or skipped one instant (the node reports them).
  std::uint64_t tilt_fallbacks = 0;
  bool gnss_valid = false;
  // The mission (mission.h): the leg in force (-1 before the start or without a plan, the number of legs in the
  // hold after the last), the plan's velocity in the stable frame, and whether a restart of the IMU's clock ended it
  // early (the plan's time is the IMU's: the agent then holds).
  int mission_leg = -1;
  Vec2 plan_velocity_mps = Vec2::Zero();
  bool mission_aborted = false;
  // Missions from the ground (Agent::commandMission): flown, refused as unflyable, and the IMU stamp from which the
  // last one flown took over.
  std::uint64_t mission_commands = 0;
  std::uint64_t mission_commands_refused = 0;
  StampNs mission_command_stamp_ns = 0;
};

}  // namespace swa::agent

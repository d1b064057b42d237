#pragma once
// What goes into and out of the agent core. Stamps are simulation (or sensor) time in nanoseconds; the core never
// reads a clock, so the same samples always give the same commands.

#include <cstdint>
#include <optional>
#include <vector>

#include "swa/agent/geometry.h"

namespace swa::agent {

using StampNs = std::int64_t;
constexpr int kAnonymousId = -1;

// Saturates instead of overflowing when the stamps are more than ~292 years apart (corrupt input): such a gap is
// "very long" for every timeout and prediction guard that reads it.
inline double secondsBetween(StampNs from, StampNs to) {
  StampNs diff = 0;
  if (__builtin_sub_overflow(to, from, &diff)) return to > from ? 1e300 : -1e300;
  return static_cast<double>(diff) * 1e-9;
}

// An accelerometer's specific force with the attitude estimate it is read with (issue #44): what PX4's
// sensor_combined + vehicle_attitude and ArduPilot's Imu give. Specific force = acceleration minus gravity, so a UAV
// at rest reads +g on body z; with the attitude, R(roll, pitch) f - g z is the kinematic acceleration whatever pushes
// the UAV (thrust, drag, gusts), where the tilt alone gives only the thrust's share.
struct AccelerometerSample {
  Vec3 specific_force_body_mps2 = Vec3::Zero();  // body frame: x forward, y left, z up
  double roll_rad = 0.0;                         // attitude estimate, in the tilt convention of tiltRotation()
  double pitch_rad = 0.0;
};

// The lateral kinematic acceleration in the level frame (x along the heading, y left) that a sample gives: the
// specific force turned into the level frame; gravity lies along level z, so the lateral part needs no removal.
inline Vec2 levelAcceleration(const AccelerometerSample& a) {
  const Vec3 level = tiltRotation(a.roll_rad, a.pitch_rad) * a.specific_force_body_mps2;
  return Vec2(level.x(), level.y());
}

// A MEMS accelerometer's largest range (+-16 g: TDK InvenSense ICM-42688-P and ICM-20948 datasheets): a specific
// force beyond it is not a measurement.
constexpr double kMaxSpecificForce_mps2 = 16.0 * kStandardGravity_mps2;

struct ImuSample {
  ImuSample() = default;
  // The tilt-only sample most callers write as {stamp, roll, pitch, heading}.
  ImuSample(StampNs stamp, double roll, double pitch, double heading,
            std::optional<AccelerometerSample> accel = std::nullopt)
      : stamp_ns(stamp), roll_rad(roll), pitch_rad(pitch), heading_rad(heading), accelerometer(accel) {}

  StampNs stamp_ns = 0;
  double roll_rad = 0.0;
  double pitch_rad = 0.0;
  double heading_rad = 0.0;                          // body x relative to stable/world x, counter-clockwise
  std::optional<AccelerometerSample> accelerometer;  // absent: a tilt-only source (the paper's)
};

struct Detection {
  int target_id = kAnonymousId;  // UVDAR-like sensors identify the neighbour; LiDAR-like ones do not
  Vec2 position_body_m = Vec2::Zero();
  std::optional<Mat2> covariance_m2;  // body frame; the configured R_o is used when absent
};

struct DetectionSet {
  StampNs stamp_ns = 0;
  std::vector<Detection> detections;
};

struct GnssSample {
  StampNs stamp_ns = 0;
  bool valid = false;
  Vec2 position_m = Vec2::Zero();  // local navigation frame (aligned with the stable frame)
  double std_m = 1.0;
};

struct VelocityCommand {
  StampNs stamp_ns = 0;           // equals the stamp of the sample that produced it
  StampNs answered_stamp_ns = 0;  // the IMU sample this command answers (latency and lockstep bookkeeping)
  std::uint64_t seq = 0;
  Vec2 velocity_mps = Vec2::Zero();  // stable frame
  // Heading rate, counter-clockwise positive (the heading's own sense). 0 holds the heading, which is all an agent
  // with an all-round sensor ever commands; always finite and within control.max_yaw_rate_radps.
  double yaw_rate_radps = 0.0;
  bool fresh = false;  // computed from this IMU sample; false: a rejected sample, answered with the previous command
};

}  // namespace swa::agent

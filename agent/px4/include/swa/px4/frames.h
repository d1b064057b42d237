#pragma once
// The one place where PX4's frames meet SWA's (ROS2-PX4-NOTES.md, DESIGN §2). No conversion anywhere else.
//
//   PX4: world NED (x north, y east, z down), body FRD (x forward, y right, z down); attitude = the Hamilton quaternion
//        (w, x, y, z) rotating FRD into NED; Euler ZYX: yaw clockwise from north, pitch positive nose up, roll positive
//        right side down. Timestamps in microseconds.
//   SWA: stable frame x east, y north; heading = yaw of body x counter-clockwise from east; tilt as the agent reads it
//        (DESIGN §3.4): body acceleration = q_c [pitch, roll] with body x forward, y left, so SWA pitch is positive
//        nose DOWN (accelerating forward) and SWA roll positive LEFT side down (accelerating left). Stamps in ns.
//   Hence: heading = pi/2 - yaw, pitch_swa = -pitch, roll_swa = -roll; a stable-frame velocity (east, north) is NED
//   (north, east, 0); a yaw rate (d heading / dt) is -yawspeed.

#include <cstdint>
#include <optional>

#include "swa/agent/samples.h"

namespace swa::px4 {

struct Quaternion {
  double w = 1.0, x = 0.0, y = 0.0, z = 0.0;  // FRD body -> NED earth
};

// PX4's Euler angles (ZYX) of an attitude [rad].
struct Euler {
  double roll = 0.0, pitch = 0.0, yaw = 0.0;
};

struct NedVelocity {
  double north = 0.0, east = 0.0, down = 0.0;  // [m/s]
};

// A quaternion PX4 could have sent: finite and of norm 1 within `kNormTolerance` (PX4 normalises; anything else is
// corrupt input, not an attitude).
constexpr double kNormTolerance = 1e-3;
bool isAttitude(const Quaternion& q);

// ZYX Euler angles of a unit quaternion, pitch in [-pi/2, pi/2]. At the singularity (|pitch| = 90 deg) only yaw -+ roll
// is defined: roll is then 0, as in PX4's matrix::Euler. Never NaN for a finite input.
Euler eulerOf(const Quaternion& q);
Quaternion quaternionOf(const Euler& e);

// SWA's attitude (roll, pitch, heading of the IMU message) of PX4's, and back. heading in (-pi, pi].
struct SwaAttitude {
  double roll_rad = 0.0, pitch_rad = 0.0, heading_rad = 0.0;
};
SwaAttitude swaAttitude(const Euler& e);
// A body vector between PX4's FRD and SWA's FLU (x forward, y left, z up): y and z flip, the same both ways. With
// swaAttitude()'s roll and pitch, SWA's tilt rotation (agent::tiltRotation) turns an FLU vector level exactly as
// PX4's attitude turns the FRD one (conjugating Ry(theta) Rx(phi) by diag(1, -1, -1) gives Ry(-theta) Rx(phi)).
inline agent::Vec3 flippedBody(const agent::Vec3& v) { return {v.x(), -v.y(), -v.z()}; }
Euler px4Euler(const SwaAttitude& a);

// Angle in (-pi, pi].
double wrapPi(double angle_rad);

// A stable-frame velocity (x east, y north) as NED with zero vertical speed (the agent commands the horizontal
// velocity only; the vehicle holds its altitude), and a NED velocity's horizontal part back in the stable frame.
NedVelocity nedOf(const agent::Vec2& stable_mps);
agent::Vec2 stableOf(const NedVelocity& ned);

// SWA's yaw rate (counter-clockwise from above, the heading's sense) as PX4's yawspeed (about NED down: clockwise
// from above), and back: heading = pi/2 - yaw, so the signs are opposite. [rad/s]
double yawspeedOf(double yaw_rate_radps);
double yawRateOf(double yawspeed_radps);

// PX4 timestamps [us] <-> SWA stamps [ns]: the same clock (the vehicle's), so detections for the agent must be stamped
// on the clock PX4 stamps its /fmu/out messages with (deploy/README.md). nullopt: beyond int64 nanoseconds.
std::optional<agent::StampNs> stampNsOf(std::uint64_t timestamp_us);
// Rounds down to the microsecond; negative stamps (before the clock's zero) have no PX4 timestamp: nullopt.
std::optional<std::uint64_t> timestampUsOf(agent::StampNs stamp_ns);

}  // namespace swa::px4

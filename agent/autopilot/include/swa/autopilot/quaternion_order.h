#pragma once
// Which field order ArduPilot's IMU message uses for its orientation, decided from the message itself
// (swa_px4_bridge --ap-quaternion auto). AP_DDS releases of 2024 write (w, x, y, z) into the (x, y, z, w) fields;
// others may not (swa/autopilot/ardupilot.h). Read in the wrong order the attitude is a wrong but valid rotation, so
// only a second witness can tell: gravity. The same message carries linear_acceleration, ArduPilot's specific force in
// FRD body axes; on a vehicle that is not accelerating it points along R^T (0, 0, -g), R the attitude in the right
// order.
//
// A sample votes only while the vehicle is disarmed (on the ground: its specific force is gravity's), when that force
// is within kStillToleranceMps2 of g and one order's gravity agrees within kAgreeDeg while the other's is off by more
// than kDisagreeDeg. kVotesNeeded votes in a row decide, once and for good; a vote the other way starts the count
// again. Not in flight: a multicopter's specific force follows its thrust axis, and one tilted by 20 degrees while
// sinking at 0.6 m/s^2 measures exactly g along its own z, which the wrong order can read as level. A bridge started
// in flight therefore decides nothing; it needs the order given.
//
// Blind spots, where the wrong order also looks level: a level vehicle heading within about kDisagreeDeg of north
// (when ArduPilot writes the ROS order) or of south (when it writes w, x, y, z). There nothing is decided until the
// vehicle is turned.

#include <cstdint>
#include <optional>

#include "swa/autopilot/ardupilot.h"

namespace swa::ardupilot {

struct SpecificForce {
  double x = 0.0, y = 0.0, z = 0.0;  // FRD body, m/s^2 (at rest (0, 0, -g) when level)
};

class QuaternionOrderFinder {
 public:
  static constexpr double kGravityMps2 = 9.80665;
  static constexpr double kStillToleranceMps2 = 0.15;
  static constexpr double kAgreeDeg = 5.0;
  static constexpr double kDisagreeDeg = 15.0;
  static constexpr int kVotesNeeded = 20;  // 0.1 to 0.2 s of ArduPilot's IMU stream

  // One message's orientation fields as they came and its linear acceleration, and whether the vehicle reports itself
  // disarmed: the order, once decided.
  std::optional<QuaternionLayout> onSample(const OrientationFields& fields, const SpecificForce& force, bool disarmed);
  std::optional<QuaternionLayout> decided() const { return decided_; }

  std::uint64_t samples() const { return samples_; }
  std::uint64_t votes() const { return votes_; }          // for either order, in all
  std::uint64_t reversals() const { return reversals_; }  // votes against the current run

 private:
  std::optional<QuaternionLayout> decided_;
  std::optional<QuaternionLayout> leading_;
  int run_ = 0;
  std::uint64_t samples_ = 0, votes_ = 0, reversals_ = 0;
};

// The angle in degrees between a specific force and the gravity an attitude (FRD -> NED) predicts for it; NaN for a
// zero or non-finite input.
double gravityMismatchDeg(const px4::Quaternion& attitude, const SpecificForce& force);
// The specific force a vehicle at rest with this attitude measures (what the simulator's stand-in sends).
SpecificForce restingForceOf(const px4::Quaternion& attitude);

}  // namespace swa::ardupilot

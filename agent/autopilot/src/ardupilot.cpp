#include "swa/autopilot/ardupilot.h"

#include <limits>

namespace swa::ardupilot {

const char* copterModeName(std::uint8_t mode) {
  switch (mode) {
    case kModeStabilize:
      return "STABILIZE";
    case 1:
      return "ACRO";
    case kModeAltHold:
      return "ALT_HOLD";
    case 3:
      return "AUTO";
    case kModeGuided:
      return "GUIDED";
    case kModeLoiter:
      return "LOITER";
    case kModeRtl:
      return "RTL";
    case 7:
      return "CIRCLE";
    case kModeLand:
      return "LAND";
    case 16:
      return "POSHOLD";
    case kModeBrake:
      return "BRAKE";
    case 20:
      return "GUIDED_NOGPS";
    case 21:
      return "SMART_RTL";
    default:
      return "other";
  }
}

std::optional<QuaternionLayout> parseQuaternionLayout(const std::string& text) {
  if (text == "ros") return QuaternionLayout::kRos;
  if (text == "wxyz") return QuaternionLayout::kWxyzInXyzw;
  return std::nullopt;
}

const char* quaternionLayoutName(QuaternionLayout layout) { return layout == QuaternionLayout::kRos ? "ros" : "wxyz"; }

px4::Quaternion attitudeOf(double x, double y, double z, double w, QuaternionLayout layout) {
  if (layout == QuaternionLayout::kWxyzInXyzw) return px4::Quaternion{x, y, z, w};
  return px4::Quaternion{w, x, y, z};
}

OrientationFields orientationFieldsOf(const px4::Quaternion& q, QuaternionLayout layout) {
  if (layout == QuaternionLayout::kWxyzInXyzw) return OrientationFields{q.w, q.x, q.y, q.z};
  return OrientationFields{q.x, q.y, q.z, q.w};
}

std::optional<std::uint64_t> timestampUsOf(std::int32_t sec, std::uint32_t nanosec) {
  if (sec < 0 || nanosec >= 1'000'000'000u) return std::nullopt;
  return static_cast<std::uint64_t>(sec) * 1'000'000u + nanosec / 1000u;
}

std::optional<RosTime> rosTimeOf(std::uint64_t timestamp_us) {
  const std::uint64_t sec = timestamp_us / 1'000'000u;
  if (sec > static_cast<std::uint64_t>(std::numeric_limits<std::int32_t>::max())) return std::nullopt;
  return RosTime{static_cast<std::int32_t>(sec), static_cast<std::uint32_t>(timestamp_us % 1'000'000u) * 1000u};
}

EnuTwist enuTwistOf(const px4::NedVelocity& velocity, double yawspeed_radps) {
  return EnuTwist{velocity.east, velocity.north, -velocity.down, px4::yawRateOf(yawspeed_radps)};
}

agent::Vec2 stableVelocityOf(const EnuTwist& twist) { return agent::Vec2(twist.east_mps, twist.north_mps); }

}  // namespace swa::ardupilot

#pragma once
// What SWA uses of PX4's vehicle states and commands (msg/VehicleStatus.msg, msg/VehicleCommand.msg,
// px4_custom_mode.h): the same values in v1.15, v1.16 and v1.17 (tests/px4/test_px4_definitions.cpp). Mirrored here so
// the pure libraries need no generated message; tests/px4/test_px4_layouts.cpp checks them against the constants of
// the IDL (idl/px4/).

#include <cstdint>

namespace swa::px4 {

constexpr std::uint8_t kArmingStateDisarmed = 1;
constexpr std::uint8_t kArmingStateArmed = 2;

constexpr std::uint8_t kNavStateAltctl = 1;  // Altitude mode: the fallback without a position
constexpr std::uint8_t kNavStatePosctl = 2;
constexpr std::uint8_t kNavStateAutoLoiter = 4;  // Hold
constexpr std::uint8_t kNavStateDescend = 12;    // the fallback of a failsafe mode that cannot run without a position
constexpr std::uint8_t kNavStateOffboard = 14;

constexpr std::uint32_t kCmdDoSetMode = 176;           // param1 = base mode flags, param2 = custom main mode
constexpr std::uint32_t kCmdComponentArmDisarm = 400;  // param1 = 1 arm, 0 disarm
constexpr float kModeFlagCustomModeEnabled = 1.0f;     // MAV_MODE_FLAG_CUSTOM_MODE_ENABLED
constexpr float kCustomMainModeOffboard = 6.0f;        // PX4_CUSTOM_MAIN_MODE_OFFBOARD

// A name for a nav_state in logs.
const char* navStateName(std::uint8_t nav_state);

}  // namespace swa::px4

#pragma once
// What of a received setpoint reaches the world (sim::World::command): the simulator's own guard on the numbers,
// since a setpoint on cmd_vel may come from any writer. Pure, no DDS entity.

#include <optional>

#include <swa/msg/VelocitySetpoint.h>

#include "swa/agent/samples.h"

namespace swa::sim_node {

// The fastest turn the simulated vehicles make [rad/s]: the upper end of control.max_yaw_rate_radps
// (agent/config/config_io.cpp), so no agent's command is changed; a faster one is clamped, which keeps the heading
// finite.
constexpr double kMaxYawRateRadps = 10.0;

// A cmd_vel setpoint as the world executes it (swa/wire/samples.h), or nullopt if a number in it is not finite:
// dropped, so the previous setpoint stays in force and keeps ageing, as the world does with a non-finite velocity.
// The yaw rate is clamped to +-kMaxYawRateRadps.
std::optional<agent::VelocityCommand> worldCommand(const msg::VelocitySetpoint& m);

// The yaw rate of PX4's trajectory_setpoint yawspeed (swa/px4/frames.h), clamped like worldCommand's. A non-finite
// yawspeed holds the heading (0): NaN is PX4's "not controlled", with which it holds the heading.
double worldYawRate(double yawspeed_radps);

}  // namespace swa::sim_node

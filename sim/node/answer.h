#pragma once
// One setpoint of a UAV as the simulator received it: from its agent's cmd_vel, or, with vehicle.interface = px4,
// a trajectory_setpoint answering an attitude sample (px4_vehicles.h turns it into the same shape, so the drivers'
// lockstep and realtime rules need not know which).

#include <chrono>

#include <swa/msg/VelocitySetpoint.h>

#include "swa/dds/participant.h"

namespace swa::sim_node {

struct Answer {
  int uav = 0;
  msg::VelocitySetpoint setpoint;                  // stable frame; answered_stamp_ns / _seq name the sample answered
                                                   // (px4: yaw_rate_radps from yawspeed, world_command.h)
  std::chrono::steady_clock::time_point received;  // when the listener got it (not when the driver drained it)
  dds::WriterGuid writer{};
  bool velocity_only = true;  // px4: position NaN (PX4 flies velocity-only setpoints in velocity control)
};

}  // namespace swa::sim_node

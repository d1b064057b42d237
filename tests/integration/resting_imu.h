#pragma once
// The IMU message of a UAV at rest, level, heading 0: what the integration and security tests write when an agent
// only needs a live IMU stream (its samples start the estimate and are answered with commands).

#include <cstdint>

#include <swa/msg/Imu.h>

#include "swa/agent/geometry.h"
#include "swa/agent/samples.h"

namespace swa::testing {

inline msg::Imu restingImu(std::uint32_t uav, agent::StampNs stamp, std::uint32_t seq = 0) {
  msg::Imu m;
  m.has_accelerometer(true);  // at rest: +g on body z (message set 5)
  m.accel_z_mps2(agent::kStandardGravity_mps2);
  m.header().stamp_ns(stamp);
  m.header().seq(seq);
  m.uav_id(uav);
  return m;
}

}  // namespace swa::testing

#include "world_command.h"

#include <algorithm>
#include <cmath>

#include "swa/agent/geometry.h"
#include "swa/px4/frames.h"
#include "swa/wire/samples.h"

namespace swa::sim_node {
namespace {

double clampYawRate(double yaw_rate_radps) { return std::clamp(yaw_rate_radps, -kMaxYawRateRadps, kMaxYawRateRadps); }

}  // namespace

std::optional<agent::VelocityCommand> worldCommand(const msg::VelocitySetpoint& m) {
  agent::VelocityCommand c = wire::fromMsg(m);
  if (!agent::isFinite(c.velocity_mps) || !std::isfinite(c.yaw_rate_radps)) return std::nullopt;
  c.yaw_rate_radps = clampYawRate(c.yaw_rate_radps);
  return c;
}

double worldYawRate(double yawspeed_radps) {
  if (!std::isfinite(yawspeed_radps)) return 0.0;
  return clampYawRate(px4::yawRateOf(yawspeed_radps));
}

}  // namespace swa::sim_node

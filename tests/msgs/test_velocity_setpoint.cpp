// VelocitySetpoint of message set 3 (yaw_rate_radps appended): its bytes on the wire, the schema a recording stores
// for it, and what of a received setpoint the simulator lets reach its world (sim/node/world_command.h).

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <swa/msg/VelocitySetpointPubSubTypes.h>

#include "roundtrip.h"
#include "swa/msg_defs/ros_definition.h"
#include "swa/sim/world.h"
#include "world_command.h"

namespace swa::sim_node {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

msg::VelocitySetpoint setpoint(double vx, double vy, double yaw_rate) {
  msg::VelocitySetpoint m;
  m.header(msg::test::make_header(20'000'000, 2));
  m.uav_id(0);
  m.vx_mps(vx);
  m.vy_mps(vy);
  m.answered_stamp_ns(20'000'000);
  m.answered_seq(2);
  m.yaw_rate_radps(yaw_rate);
  return m;
}

// The value at `offset` of the message body (after the 4-byte encapsulation header).
template <class T>
T bodyAt(const std::vector<std::uint8_t>& b, std::size_t offset) {
  T v{};
  EXPECT_LE(4 + offset + sizeof(T), b.size()) << "offset " << offset;
  if (4 + offset + sizeof(T) <= b.size()) std::memcpy(&v, b.data() + 4 + offset, sizeof(T));
  return v;
}

TEST(VelocitySetpointLayout, TheYawRateIsAppendedSoMessageSet2ReadsTheRest) {
  // GIVEN a setpoint with every field set
  msg::VelocitySetpoint m = setpoint(-1.5, 2.25, 0.3);
  m.uav_id(7);
  // WHEN it is serialised as a DataWriter does (XCDR1, little endian)
  msg::VelocitySetpointPubSubType type;
  eprosima::fastrtps::rtps::SerializedPayload_t p(type.getSerializedSizeProvider(&m)());
  ASSERT_TRUE(type.serialize(&m, &p));
  const std::vector<std::uint8_t> b(p.data, p.data + p.length);
  // THEN set 2's fields keep set 2's offsets (the first 44 bytes of the body are a set-2 setpoint) ...
  EXPECT_EQ(bodyAt<std::int64_t>(b, 0), 20'000'000);
  EXPECT_EQ(bodyAt<std::uint32_t>(b, 8), 2u);
  EXPECT_EQ(bodyAt<std::uint32_t>(b, 12), 7u);
  EXPECT_EQ(bodyAt<double>(b, 16), -1.5);
  EXPECT_EQ(bodyAt<double>(b, 24), 2.25);
  EXPECT_EQ(bodyAt<std::int64_t>(b, 32), 20'000'000);
  EXPECT_EQ(bodyAt<std::uint32_t>(b, 40), 2u);
  // ... and the yaw rate follows them, aligned to 8, ending the body
  EXPECT_EQ(bodyAt<double>(b, 48), 0.3);
  EXPECT_EQ(b.size(), 4u + 56u);
  // AND a set-2 writer's setpoint (those 44 bytes alone) does not pass for set 3 with a made-up yaw rate
  eprosima::fastrtps::rtps::SerializedPayload_t set2(4 + 44);
  std::memcpy(set2.data, b.data(), 4 + 44);
  set2.length = 4 + 44;
  msg::VelocitySetpoint out;
  EXPECT_FALSE(type.deserialize(&set2, &out));
}

TEST(VelocitySetpointSchema, TheRecordedDefinitionHasTheYawRateLast) {
  // GIVEN the ros2msg definition a recording stores for cmd_vel (built from idl/swa_msgs/msg/VelocitySetpoint.msg)
  const std::optional<std::string> definition = msg_defs::rosDefinition("VelocitySetpoint");
  ASSERT_TRUE(definition);
  // THEN it declares the yaw rate, after answered_seq and before the MessageHeader dependency
  const std::size_t seq = definition->find("\nuint32 answered_seq");
  const std::size_t yaw = definition->find("\nfloat64 yaw_rate_radps");
  const std::size_t header = definition->find("MSG: swa_msgs/MessageHeader");
  ASSERT_NE(seq, std::string::npos) << *definition;
  ASSERT_NE(yaw, std::string::npos) << *definition;
  ASSERT_NE(header, std::string::npos) << *definition;
  EXPECT_LT(seq, yaw);
  EXPECT_LT(yaw, header);
}

TEST(WorldCommand, AFiniteSetpointReachesTheWorldUnchanged) {
  // GIVEN an agent's setpoint turning left at a rate that survives no arithmetic
  const msg::VelocitySetpoint m = setpoint(0.1, -1.0 / 9.0, 1.0 / 3.0);
  // WHEN the simulator reads it THEN the world gets every value as sent
  const std::optional<agent::VelocityCommand> c = worldCommand(m);
  ASSERT_TRUE(c);
  EXPECT_EQ(c->velocity_mps, agent::Vec2(0.1, -1.0 / 9.0));
  EXPECT_EQ(c->yaw_rate_radps, 1.0 / 3.0);
  EXPECT_EQ(c->answered_stamp_ns, 20'000'000);
}

TEST(WorldCommand, ANonFiniteSetpointIsDroppedAndAHugeYawRateClamped) {
  // WHEN a setpoint carries a NaN or infinite velocity or yaw rate THEN it is dropped, as a whole
  EXPECT_FALSE(worldCommand(setpoint(kNaN, 0.0, 0.0)));
  EXPECT_FALSE(worldCommand(setpoint(0.0, kInf, 0.0)));
  EXPECT_FALSE(worldCommand(setpoint(0.5, 0.5, kNaN)));
  EXPECT_FALSE(worldCommand(setpoint(0.5, 0.5, -kInf)));
  // WHEN the yaw rate is finite but beyond any agent's limit THEN it is clamped, the velocity kept
  const std::optional<agent::VelocityCommand> huge = worldCommand(setpoint(0.5, 0.25, -1e300));
  ASSERT_TRUE(huge);
  EXPECT_EQ(huge->yaw_rate_radps, -kMaxYawRateRadps);
  EXPECT_EQ(huge->velocity_mps, agent::Vec2(0.5, 0.25));
  // AND PX4's yawspeed (clockwise positive) becomes the world's rate with the sign flipped; NaN (PX4: not
  // controlled) holds the heading, and so does any other non-finite value
  EXPECT_EQ(worldYawRate(-0.3), 0.3);
  EXPECT_EQ(worldYawRate(kNaN), 0.0);
  EXPECT_EQ(worldYawRate(kInf), 0.0);
  EXPECT_EQ(worldYawRate(1e300), -kMaxYawRateRadps);
}

TEST(WorldCommand, RogueYawRatesNeverMakeTheSimulatedHeadingNonFinite) {
  // GIVEN a world of one UAV heading east, no wind
  sim::Scenario s;
  s.uav_count = 1;
  s.seed = 3;
  s.formation.position_jitter_m = 0.0;
  s.dynamics.heading = sim::HeadingMode::kZero;
  s.dynamics.heading_rate_std_radps = 0.0;
  s.wind.gust_std = 0.0;
  s.wind.common_std = 0.0;
  sim::World world(s);
  // WHEN it is sent, step after step for 2 s, setpoints with NaN, infinite and huge yaw rates, through the
  // simulator's guard as the simulator node applies them
  const double rogue[] = {kNaN, kInf, -kInf, 1e300, -1e300, std::numeric_limits<double>::max()};
  for (int k = 0; k < 200; ++k) {
    if (const auto c = worldCommand(setpoint(0.0, 0.0, rogue[k % 6]))) world.command(0, *c);
    world.step();
    // THEN the heading stays finite throughout
    ASSERT_TRUE(std::isfinite(world.truth()[0].heading_rad)) << "step " << k;
  }
  // WHEN another such world is sent 1 s of a genuine left turn THEN its heading turns counter-clockwise: the yaw
  // rate reaches the world (less than 0.3 rad: the world's yaw rate lags the command)
  sim::World turned(s);
  for (int k = 0; k < 100; ++k) {
    turned.command(0, *worldCommand(setpoint(0.0, 0.0, 0.3)));
    turned.step();
  }
  EXPECT_GT(turned.truth()[0].heading_rad, 0.05);
  EXPECT_LT(turned.truth()[0].heading_rad, 0.3);
}

}  // namespace
}  // namespace swa::sim_node

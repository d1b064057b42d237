// PX4 v1.15's messages on the wire, byte for byte: each field at the offset the v1.15 .msg layout gives it in XCDR1
// (classic CDR, little endian, alignment = min(size, 8) counted after the 4-byte encapsulation header), as PX4's
// uXRCE-DDS client writes them. A field added, dropped, reordered or resized in idl/px4/ moves an offset and fails
// here. Also: the constants SWA's pure PX4 library mirrors (swa/px4/vehicle.h) are those of the IDL.

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <vector>

#include <swa/px4/OffboardControlMode_v1_15PubSubTypes.h>
#include <swa/px4/TrajectorySetpoint_v1_15PubSubTypes.h>
#include <swa/px4/VehicleAttitude_v1_15PubSubTypes.h>
#include <swa/px4/VehicleCommandAck_v1_15PubSubTypes.h>
#include <swa/px4/VehicleCommand_v1_15PubSubTypes.h>
#include <swa/px4/VehicleStatus_v1_15PubSubTypes.h>

#include "swa/px4/vehicle.h"

namespace swa::px4 {
namespace {

using Bytes = std::vector<std::uint8_t>;
constexpr std::size_t kEncapsulation = 4;

template <class PubSubType>
Bytes wire(typename PubSubType::type m) {
  PubSubType type;
  eprosima::fastrtps::rtps::SerializedPayload_t p(type.getSerializedSizeProvider(&m)());
  EXPECT_TRUE(type.serialize(&m, &p));
  return Bytes(p.data, p.data + p.length);
}

// The value at `offset` of the message body.
template <class T>
T at(const Bytes& b, std::size_t offset) {
  T v{};
  EXPECT_LE(kEncapsulation + offset + sizeof(T), b.size()) << "offset " << offset;
  if (kEncapsulation + offset + sizeof(T) <= b.size()) std::memcpy(&v, b.data() + kEncapsulation + offset, sizeof(T));
  return v;
}

// The body ends exactly where the last field ends (no trailing padding in XCDR1).
void expectBodySize(const Bytes& b, std::size_t size) {
  EXPECT_EQ(b.size(), kEncapsulation + size);
  ASSERT_GE(b.size(), kEncapsulation);
  EXPECT_EQ(b[0], 0x00);  // CDR_LE: classic CDR, little endian
  EXPECT_EQ(b[1], 0x01);
}

TEST(Px4Layouts, VehicleAttitude) {
  px4_msgs::msg::VehicleAttitude m;
  m.timestamp(0x1111111111111111ULL);
  m.timestamp_sample(0x2222222222222222ULL);
  m.q({0.5f, -0.25f, 0.125f, 1.0f});
  m.delta_q_reset({2.0f, 3.0f, 4.0f, 5.0f});
  m.quat_reset_counter(0x7b);
  const Bytes b = wire<px4_msgs::msg::VehicleAttitudePubSubType>(m);
  expectBodySize(b, 49);
  EXPECT_EQ(at<std::uint64_t>(b, 0), 0x1111111111111111ULL);
  EXPECT_EQ(at<std::uint64_t>(b, 8), 0x2222222222222222ULL);
  EXPECT_EQ(at<float>(b, 16), 0.5f);
  EXPECT_EQ(at<float>(b, 28), 1.0f);
  EXPECT_EQ(at<float>(b, 32), 2.0f);
  EXPECT_EQ(at<float>(b, 44), 5.0f);
  EXPECT_EQ(at<std::uint8_t>(b, 48), 0x7b);
  EXPECT_EQ(px4_msgs::msg::VehicleAttitudePubSubType().getName(), std::string("px4_msgs::msg::dds_::VehicleAttitude_"));
}

TEST(Px4Layouts, VehicleStatus) {
  px4_msgs::msg::VehicleStatus m;
  m.timestamp(1);
  m.armed_time(2);
  m.takeoff_time(3);
  m.arming_state(4);
  m.latest_arming_reason(5);
  m.latest_disarming_reason(6);
  m.nav_state_timestamp(7);
  m.nav_state_user_intention(8);
  m.nav_state(9);
  m.executor_in_charge(10);
  m.valid_nav_states_mask(0x0b0b0b0b);
  m.can_set_nav_states_mask(0x0c0c0c0c);
  m.failure_detector_status(0x0d0d);
  m.hil_state(14);
  m.vehicle_type(15);
  m.failsafe(true);
  m.failsafe_defer_state(17);
  m.gcs_connection_lost_counter(18);
  m.system_type(19);
  m.system_id(20);
  m.component_id(21);
  m.pre_flight_checks_pass(true);
  const Bytes b = wire<px4_msgs::msg::VehicleStatusPubSubType>(m);
  expectBodySize(b, 82);
  EXPECT_EQ(at<std::uint64_t>(b, 0), 1u);
  EXPECT_EQ(at<std::uint64_t>(b, 8), 2u);
  EXPECT_EQ(at<std::uint64_t>(b, 16), 3u);
  EXPECT_EQ(at<std::uint8_t>(b, 24), 4);
  EXPECT_EQ(at<std::uint8_t>(b, 25), 5);
  EXPECT_EQ(at<std::uint8_t>(b, 26), 6);
  EXPECT_EQ(at<std::uint64_t>(b, 32), 7u);
  EXPECT_EQ(at<std::uint8_t>(b, 40), 8);
  EXPECT_EQ(at<std::uint8_t>(b, 41), 9);
  EXPECT_EQ(at<std::uint8_t>(b, 42), 10);
  EXPECT_EQ(at<std::uint32_t>(b, 44), 0x0b0b0b0bu);
  EXPECT_EQ(at<std::uint32_t>(b, 48), 0x0c0c0c0cu);
  EXPECT_EQ(at<std::uint16_t>(b, 52), 0x0d0d);
  EXPECT_EQ(at<std::uint8_t>(b, 54), 14);
  EXPECT_EQ(at<std::uint8_t>(b, 55), 15);
  EXPECT_EQ(at<std::uint8_t>(b, 56), 1);
  EXPECT_EQ(at<std::uint8_t>(b, 58), 17);
  EXPECT_EQ(at<std::uint8_t>(b, 60), 18);
  EXPECT_EQ(at<std::uint8_t>(b, 66), 19);
  EXPECT_EQ(at<std::uint8_t>(b, 67), 20);
  EXPECT_EQ(at<std::uint8_t>(b, 68), 21);
  EXPECT_EQ(at<std::uint8_t>(b, 81), 1);
}

TEST(Px4Layouts, OffboardControlMode) {
  px4_msgs::msg::OffboardControlMode m;
  m.timestamp(0x0102030405060708ULL);
  m.velocity(true);
  m.direct_actuator(true);
  const Bytes b = wire<px4_msgs::msg::OffboardControlModePubSubType>(m);
  expectBodySize(b, 15);
  EXPECT_EQ(at<std::uint64_t>(b, 0), 0x0102030405060708ULL);
  EXPECT_EQ(at<std::uint8_t>(b, 8), 0);   // position
  EXPECT_EQ(at<std::uint8_t>(b, 9), 1);   // velocity
  EXPECT_EQ(at<std::uint8_t>(b, 14), 1);  // direct_actuator
}

TEST(Px4Layouts, TrajectorySetpoint) {
  px4_msgs::msg::TrajectorySetpoint m;
  m.timestamp(9);
  m.position({1.0f, 2.0f, 3.0f});
  m.velocity({4.0f, 5.0f, 6.0f});
  m.acceleration({7.0f, 8.0f, 9.0f});
  m.jerk({10.0f, 11.0f, 12.0f});
  m.yaw(13.0f);
  m.yawspeed(14.0f);
  const Bytes b = wire<px4_msgs::msg::TrajectorySetpointPubSubType>(m);
  expectBodySize(b, 64);
  EXPECT_EQ(at<std::uint64_t>(b, 0), 9u);
  EXPECT_EQ(at<float>(b, 8), 1.0f);
  EXPECT_EQ(at<float>(b, 20), 4.0f);
  EXPECT_EQ(at<float>(b, 28), 6.0f);
  EXPECT_EQ(at<float>(b, 32), 7.0f);
  EXPECT_EQ(at<float>(b, 44), 10.0f);
  EXPECT_EQ(at<float>(b, 56), 13.0f);
  EXPECT_EQ(at<float>(b, 60), 14.0f);
}

TEST(Px4Layouts, VehicleCommand) {
  px4_msgs::msg::VehicleCommand m;
  m.timestamp(1);
  m.param1(2.0f);
  m.param4(5.0f);
  m.param5(6.0);
  m.param6(7.0);
  m.param7(8.0f);
  m.command(kCmdDoSetMode);
  m.target_system(10);
  m.target_component(11);
  m.source_system(12);
  m.source_component(0x0d0d);
  m.confirmation(14);
  m.from_external(true);
  const Bytes b = wire<px4_msgs::msg::VehicleCommandPubSubType>(m);
  expectBodySize(b, 56);
  EXPECT_EQ(at<float>(b, 8), 2.0f);
  EXPECT_EQ(at<float>(b, 20), 5.0f);
  EXPECT_EQ(at<double>(b, 24), 6.0);
  EXPECT_EQ(at<double>(b, 32), 7.0);
  EXPECT_EQ(at<float>(b, 40), 8.0f);
  EXPECT_EQ(at<std::uint32_t>(b, 44), 176u);
  EXPECT_EQ(at<std::uint8_t>(b, 48), 10);
  EXPECT_EQ(at<std::uint8_t>(b, 49), 11);
  EXPECT_EQ(at<std::uint8_t>(b, 50), 12);
  EXPECT_EQ(at<std::uint16_t>(b, 52), 0x0d0d);
  EXPECT_EQ(at<std::uint8_t>(b, 54), 14);
  EXPECT_EQ(at<std::uint8_t>(b, 55), 1);
}

TEST(Px4Layouts, VehicleCommandAck) {
  px4_msgs::msg::VehicleCommandAck m;
  m.timestamp(1);
  m.command(kCmdComponentArmDisarm);
  m.result(3);
  m.result_param1(4);
  m.result_param2(-5);
  m.target_system(6);
  m.target_component(0x0707);
  m.from_external(true);
  const Bytes b = wire<px4_msgs::msg::VehicleCommandAckPubSubType>(m);
  expectBodySize(b, 25);
  EXPECT_EQ(at<std::uint32_t>(b, 8), 400u);
  EXPECT_EQ(at<std::uint8_t>(b, 12), 3);
  EXPECT_EQ(at<std::uint8_t>(b, 13), 4);
  EXPECT_EQ(at<std::int32_t>(b, 16), -5);
  EXPECT_EQ(at<std::uint8_t>(b, 20), 6);
  EXPECT_EQ(at<std::uint16_t>(b, 22), 0x0707);
  EXPECT_EQ(at<std::uint8_t>(b, 24), 1);
}

TEST(Px4Layouts, MirroredConstantsAreTheIdls) {
  EXPECT_EQ(kArmingStateArmed, px4_msgs::msg::VehicleStatus__ARMING_STATE_ARMED);
  EXPECT_EQ(kArmingStateDisarmed, px4_msgs::msg::VehicleStatus__ARMING_STATE_DISARMED);
  EXPECT_EQ(kNavStateOffboard, px4_msgs::msg::VehicleStatus__NAVIGATION_STATE_OFFBOARD);
  EXPECT_EQ(kNavStateAutoLoiter, px4_msgs::msg::VehicleStatus__NAVIGATION_STATE_AUTO_LOITER);
  EXPECT_EQ(kNavStatePosctl, px4_msgs::msg::VehicleStatus__NAVIGATION_STATE_POSCTL);
  EXPECT_EQ(kCmdDoSetMode, px4_msgs::msg::VehicleCommand__VEHICLE_CMD_DO_SET_MODE);
  EXPECT_EQ(kCmdComponentArmDisarm, px4_msgs::msg::VehicleCommand__VEHICLE_CMD_COMPONENT_ARM_DISARM);
  EXPECT_EQ(kCustomMainModeOffboard, px4_msgs::msg::VehicleCommand__PX4_CUSTOM_MAIN_MODE_OFFBOARD);
  EXPECT_EQ(kModeFlagCustomModeEnabled, px4_msgs::msg::VehicleCommand__MODE_FLAG_CUSTOM_MODE_ENABLED);
}

}  // namespace
}  // namespace swa::px4

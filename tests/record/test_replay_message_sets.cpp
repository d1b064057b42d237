// Recordings of an earlier message set replay: message set 5 appended the accelerometer to Imu, and an IMU sample
// recorded by set 4 is read as set 5 without one (dds::upgradeAppended, which swa_replay applies on reading).
#include <cstdint>

#include <gtest/gtest.h>

#include <swa/msg/DetectionsPubSubTypes.h>
#include <swa/msg/ImuPubSubTypes.h>

#include "swa/dds/raw_type.h"

namespace swa {
namespace {

msg::Imu imuOfSet4() {
  msg::Imu m;
  m.header().stamp_ns(123456789);
  m.header().seq(42);
  m.uav_id(3);
  m.roll_rad(0.01);
  m.pitch_rad(-0.02);
  m.heading_rad(2.5);
  return m;
}

TEST(ReplayMessageSets, AnImuSampleOfMessageSet4IsReadAsSet5WithoutAnAccelerometer) {
  // GIVEN the bytes a set-4 writer sent: today's encoding cut after heading_rad (4 bytes of encapsulation, the
  // header's 12, uav_id's 4 and three doubles: 44), which is what set 4's layout is, as set 5 only appended fields
  msg::Imu full = imuOfSet4();
  full.has_accelerometer(true);
  full.accel_z_mps2(9.8);
  dds::Payload set4 = dds::encodePayload<msg::ImuPubSubType>(full);
  ASSERT_GT(set4.size(), 44u);
  set4.resize(44);
  // WHEN today's reader decodes it, it is refused (too short) ...
  msg::Imu out;
  EXPECT_FALSE(dds::decodePayload<msg::ImuPubSubType>(set4, out));
  // ... THEN upgraded, it decodes to the same sample without an accelerometer
  const dds::Payload upgraded = dds::upgradeAppended<msg::ImuPubSubType>(set4, 44);
  ASSERT_TRUE(dds::decodePayload<msg::ImuPubSubType>(upgraded, out));
  EXPECT_EQ(out.header().stamp_ns(), 123456789);
  EXPECT_EQ(out.header().seq(), 42u);
  EXPECT_EQ(out.uav_id(), 3u);
  EXPECT_EQ(out.roll_rad(), 0.01);
  EXPECT_EQ(out.pitch_rad(), -0.02);
  EXPECT_EQ(out.heading_rad(), 2.5);
  EXPECT_FALSE(out.has_accelerometer());
  EXPECT_EQ(out.accel_z_mps2(), 0.0);
}

TEST(ReplayMessageSets, TodaysSamplesAndBrokenOnesPassUnchanged) {
  // GIVEN a set-5 sample, and a payload too short to be any set's Imu
  msg::Imu m = imuOfSet4();
  m.has_accelerometer(true);
  m.accel_x_mps2(0.25);
  const dds::Payload today = dds::encodePayload<msg::ImuPubSubType>(m);
  const dds::Payload broken = {0x00, 0x01, 0x00, 0x00, 0x07};
  // THEN the first comes back byte for byte, and the second as it was (it still does not decode: dropped later)
  EXPECT_EQ(dds::upgradeAppended<msg::ImuPubSubType>(today, 44), today);
  EXPECT_EQ(dds::upgradeAppended<msg::ImuPubSubType>(broken, 44), broken);
}

}  // namespace
}  // namespace swa

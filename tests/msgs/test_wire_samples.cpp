// The UAV's sensor and command messages: each type survives the DDS serialisation path, and the agent core's
// samples go through the wire bridge (swa/wire/samples.h) and the wire and come back bit for bit, so a lockstep DDS
// run sees exactly what the in-process closed loop sees.

#include <cmath>

#include <swa/msg/DetectionsPubSubTypes.h>
#include <swa/msg/GnssFixPubSubTypes.h>
#include <swa/msg/ImuPubSubTypes.h>
#include <swa/msg/SensorFramePubSubTypes.h>
#include <swa/msg/VelocitySetpointPubSubTypes.h>

#include "roundtrip.h"
#include "swa/wire/samples.h"

namespace swa::wire {
namespace {

using msg::test::make_header;
using msg::test::through_the_wire;

msg::Detection detection(std::int32_t id, double x_m, double y_m, bool has_cov) {
  msg::Detection d;
  d.target_id(id);
  d.x_m(x_m);
  d.y_m(y_m);
  d.has_covariance(has_cov);
  d.cov_xx_m2(0.5 + x_m * 0.01);
  d.cov_xy_m2(-0.125);
  d.cov_yy_m2(0.75 + y_m * 0.01);
  return d;
}

TEST(WireMessages, SensorAndCommandMessagesSurviveSerialisation) {
  // GIVEN one message of each type with every field set to a distinct non-default value
  msg::Imu imu;
  imu.header(make_header(1'234'567'890'123, 42));
  imu.uav_id(7);
  imu.roll_rad(0.125);
  imu.pitch_rad(-0.25);
  imu.heading_rad(2.5);
  msg::Detections det;
  det.header(make_header(2'500'000'000, 250));
  det.observer_id(4);
  det.items().push_back(detection(9, 10.5, -3.25, true));
  det.items().push_back(detection(msg::ANONYMOUS_ID, -7.75, 1.125, false));
  msg::GnssFix fix;
  fix.header(make_header(5'000'000'001, 9));
  fix.uav_id(3);
  fix.valid(true);
  fix.x_m(-120.5);
  fix.y_m(64.25);
  fix.std_m(1.75);
  msg::VelocitySetpoint sp;
  sp.header(make_header(7'000'000'003, 101));
  sp.uav_id(11);
  sp.vx_mps(-1.5);
  sp.vy_mps(2.75);
  sp.answered_stamp_ns(6'990'000'000);
  sp.answered_seq(100);
  sp.yaw_rate_radps(-0.4375);
  // WHEN each goes through serialize/deserialize THEN each copy equals its original, under its qualified type name
  EXPECT_DOUBLE_EQ(through_the_wire<msg::ImuPubSubType>(imu, "swa::msg::Imu").heading_rad(), 2.5);
  EXPECT_EQ(through_the_wire<msg::DetectionsPubSubType>(det, "swa::msg::Detections").items()[1].target_id(), -1);
  EXPECT_STREQ(msg::DetectionPubSubType().getName(), "swa::msg::Detection");
  EXPECT_TRUE(through_the_wire<msg::GnssFixPubSubType>(fix, "swa::msg::GnssFix").valid());
  const msg::VelocitySetpoint sp2 = through_the_wire<msg::VelocitySetpointPubSubType>(sp, "swa::msg::VelocitySetpoint");
  EXPECT_EQ(sp2.answered_seq(), 100u);
  EXPECT_EQ(sp2.yaw_rate_radps(), -0.4375);
}

TEST(WireMessages, OversizeDetectionListStillReachesTheConsumer) {
  // GIVEN more detections than the consumer's bound (64) and than the 100 elements fastddsgen assumes for unbounded
  // sequences when computing the type's max size
  msg::Detections in;
  in.observer_id(1);
  for (std::int32_t i = 0; i < 150; ++i) in.items().push_back(detection(i, i * 0.5, -i * 0.25, (i % 2) == 0));
  // WHEN it goes through serialize/deserialize
  const msg::Detections out = through_the_wire<msg::DetectionsPubSubType>(in, "swa::msg::Detections");
  // THEN nothing is truncated: rejecting oversize input is the consumer's job, not the transport's
  EXPECT_EQ(out.items().size(), 150u);
}

TEST(WireMessages, ASensorFrameCarriesItsPartsUnchangedAndOnlyThoseItHas) {
  // GIVEN a simulator step's three samples, and a frame of them (issue #29)
  msg::Imu imu;
  imu.header(make_header(3'000'000'000, 301));
  imu.uav_id(5);
  imu.roll_rad(-0.0625);
  imu.pitch_rad(0.03125);
  imu.heading_rad(-1.75);
  msg::Detections det;
  det.header(make_header(3'000'000'000, 31));
  det.observer_id(5);
  for (std::int32_t i = 0; i < 150; ++i) det.items().push_back(detection(i, i * 0.5, -i * 0.25, (i % 2) == 0));
  msg::GnssFix fix;
  fix.header(make_header(3'000'000'000, 31));
  fix.uav_id(5);
  fix.valid(false);
  msg::SensorFrame frame;
  frame.header(make_header(3'000'000'000, 301));
  frame.uav_id(5);
  frame.imu_sample().push_back(imu);
  frame.detection_set().push_back(det);
  frame.gnss_fix().push_back(fix);
  // WHEN it goes through serialize/deserialize
  const msg::SensorFrame out = through_the_wire<msg::SensorFramePubSubType>(frame, "swa::msg::SensorFrame");
  // THEN each part is its original, a detection set beyond fastddsgen's assumed 100 elements included
  ASSERT_EQ(out.imu_sample().size(), 1u);
  ASSERT_EQ(out.detection_set().size(), 1u);
  ASSERT_EQ(out.gnss_fix().size(), 1u);
  EXPECT_TRUE(out.imu_sample()[0] == imu);
  EXPECT_TRUE(out.detection_set()[0] == det);
  EXPECT_EQ(out.detection_set()[0].items().size(), 150u);
  EXPECT_TRUE(out.gnss_fix()[0] == fix);
  EXPECT_EQ(out.header().seq(), 301u);

  // AND a step without detections or fix sends only its IMU sample
  msg::SensorFrame imu_only;
  imu_only.uav_id(5);
  imu_only.imu_sample().push_back(imu);
  const msg::SensorFrame out2 = through_the_wire<msg::SensorFramePubSubType>(imu_only, "swa::msg::SensorFrame");
  EXPECT_EQ(out2.imu_sample().size(), 1u);
  EXPECT_TRUE(out2.detection_set().empty());
  EXPECT_TRUE(out2.gnss_fix().empty());
}

TEST(WireSamples, TheAccelerometerOfMessageSet5SurvivesTheWireBitForBitAndItsAbsenceToo) {
  // GIVEN an IMU sample with an accelerometer part of values no arithmetic leaves alone, and one without
  agent::AccelerometerSample acc;
  acc.specific_force_body_mps2 = agent::Vec3(1.0 / 3.0, -1e-17, 9.80665);
  acc.roll_rad = -1.0 / 7.0;
  acc.pitch_rad = std::nextafter(0.1, 1.0);
  const agent::ImuSample with{5, 0.1, 0.2, 0.3, acc};
  const agent::ImuSample without{6, 0.1, 0.2, 0.3};
  // WHEN each goes sample -> message -> wire -> message -> sample
  const agent::ImuSample with2 = fromMsg(through_the_wire<msg::ImuPubSubType>(toMsg(with, 1, 2), "swa::msg::Imu"));
  const agent::ImuSample without2 =
      fromMsg(through_the_wire<msg::ImuPubSubType>(toMsg(without, 1, 3), "swa::msg::Imu"));
  // THEN the accelerometer comes back bit for bit, and its absence stays an absence
  ASSERT_TRUE(with2.accelerometer.has_value());
  EXPECT_EQ(with2.accelerometer->specific_force_body_mps2, acc.specific_force_body_mps2);
  EXPECT_EQ(with2.accelerometer->roll_rad, acc.roll_rad);
  EXPECT_EQ(with2.accelerometer->pitch_rad, acc.pitch_rad);
  EXPECT_FALSE(without2.accelerometer.has_value());
  EXPECT_EQ(without2.pitch_rad, 0.2);
}

TEST(WireSamples, SamplesSurviveTheBridgeAndTheWireBitForBit) {
  // GIVEN samples with values that do not survive any arithmetic
  const agent::ImuSample imu{123456789, 0.1234567890123, -1e-17, 3.0 * M_PI};
  agent::DetectionSet det;
  det.stamp_ns = 42;
  agent::Detection a;
  a.target_id = 5;
  a.position_body_m = agent::Vec2(1.0 / 3.0, -7.25);
  agent::Detection b;
  b.target_id = agent::kAnonymousId;
  b.position_body_m = agent::Vec2(std::nextafter(1.0, 2.0), 0.0);
  agent::Mat2 c;
  c << 0.2, 0.01, 0.01, 0.3;
  b.covariance_m2 = c;
  det.detections = {a, b};
  const agent::GnssSample g{99, true, agent::Vec2(12.5, -3.0 / 7.0), 0.5};
  agent::VelocityCommand cmd;
  cmd.stamp_ns = 1000;
  cmd.answered_stamp_ns = 1000;
  cmd.velocity_mps = agent::Vec2(0.1, -1.0 / 9.0);
  cmd.yaw_rate_radps = -1.0 / 7.0;

  // WHEN each goes sample -> message -> wire -> message -> sample
  const msg::Imu imu_msg = through_the_wire<msg::ImuPubSubType>(toMsg(imu, 3, 7), "swa::msg::Imu");
  const agent::ImuSample imu2 = fromMsg(imu_msg);
  const agent::DetectionSet det2 =
      fromMsg(through_the_wire<msg::DetectionsPubSubType>(toMsg(det, 1, 2), "swa::msg::Detections"));
  const agent::GnssSample g2 = fromMsg(through_the_wire<msg::GnssFixPubSubType>(toMsg(g, 0, 1), "swa::msg::GnssFix"));
  const msg::VelocitySetpoint sp =
      through_the_wire<msg::VelocitySetpointPubSubType>(toMsg(cmd, 2, 11, 17), "swa::msg::VelocitySetpoint");
  const agent::VelocityCommand cmd2 = fromMsg(sp);

  // THEN every value is the same bit for bit, and the message carries who sent it and which sample it answers
  EXPECT_EQ(imu2.stamp_ns, imu.stamp_ns);
  EXPECT_EQ(imu2.roll_rad, imu.roll_rad);
  EXPECT_EQ(imu2.pitch_rad, imu.pitch_rad);
  EXPECT_EQ(imu2.heading_rad, imu.heading_rad);
  EXPECT_EQ(imu_msg.uav_id(), 3u);
  EXPECT_EQ(imu_msg.header().seq(), 7u);
  ASSERT_EQ(det2.detections.size(), 2u);
  EXPECT_EQ(det2.stamp_ns, 42);
  EXPECT_EQ(det2.detections[0].target_id, 5);
  EXPECT_EQ(det2.detections[0].position_body_m, a.position_body_m);
  EXPECT_FALSE(det2.detections[0].covariance_m2.has_value());
  EXPECT_EQ(det2.detections[1].target_id, agent::kAnonymousId);
  EXPECT_EQ(det2.detections[1].position_body_m, b.position_body_m);
  ASSERT_TRUE(det2.detections[1].covariance_m2.has_value());
  EXPECT_EQ(*det2.detections[1].covariance_m2, c);
  EXPECT_EQ(g2.stamp_ns, 99);
  EXPECT_TRUE(g2.valid);
  EXPECT_EQ(g2.position_m, g.position_m);
  EXPECT_EQ(g2.std_m, 0.5);
  EXPECT_EQ(sp.answered_seq(), 17u);
  EXPECT_EQ(sp.uav_id(), 2u);
  EXPECT_EQ(cmd2.answered_stamp_ns, 1000);
  EXPECT_EQ(cmd2.seq, 11u);
  EXPECT_EQ(cmd2.velocity_mps, cmd.velocity_mps);
  EXPECT_EQ(sp.yaw_rate_radps(), cmd.yaw_rate_radps);
  EXPECT_EQ(cmd2.yaw_rate_radps, cmd.yaw_rate_radps);
}

}  // namespace
}  // namespace swa::wire

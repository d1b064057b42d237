// The agents' command as geometry_msgs/TwistStamped (swa/wire/ros_types.h), what ROS tools show on
// /swa/uav<I>/cmd_vel_stamped: REP-103 ENU at the UAV, so the stable frame's axes and the yaw rate carry over as they
// are (angular.z about z up is counter-clockwise seen from above, the sense of SWA's heading).

#include <gtest/gtest.h>

#include "swa/wire/ros_types.h"

namespace swa::wire {
namespace {

TEST(RosTypes, TheCommandIsATwistInEnuWithTheYawRateAboutZ) {
  // GIVEN UAV 3's setpoint: 0.75 m/s east, 1.25 m/s south, turning left at 1/3 rad/s
  msg::VelocitySetpoint m;
  m.header().stamp_ns(-1'250'000'000);
  m.header().seq(8);
  m.uav_id(3);
  m.vx_mps(0.75);
  m.vy_mps(-1.25);
  m.answered_stamp_ns(-1'250'000'000);
  m.answered_seq(8);
  m.yaw_rate_radps(1.0 / 3.0);
  // WHEN it becomes a TwistStamped
  const geometry_msgs::msg::TwistStamped t = toTwistStamped(m);
  // THEN the header names the UAV's ENU frame at the setpoint's stamp (nanosec in [0, 1e9) below zero too)
  EXPECT_EQ(t.header().frame_id(), "swa/uav3/enu");
  EXPECT_EQ(t.header().stamp().sec(), -2);
  EXPECT_EQ(t.header().stamp().nanosec(), 750'000'000u);
  // AND the horizontal velocity is linear x east, y north; the yaw rate angular z, unchanged; the rest 0
  EXPECT_EQ(t.twist().linear().x(), 0.75);
  EXPECT_EQ(t.twist().linear().y(), -1.25);
  EXPECT_EQ(t.twist().linear().z(), 0.0);
  EXPECT_EQ(t.twist().angular().x(), 0.0);
  EXPECT_EQ(t.twist().angular().y(), 0.0);
  EXPECT_EQ(t.twist().angular().z(), 1.0 / 3.0);
  // AND holding the heading is angular z 0
  m.yaw_rate_radps(0.0);
  EXPECT_EQ(toTwistStamped(m).twist().angular().z(), 0.0);
}

}  // namespace
}  // namespace swa::wire

// The names of SWA's topics and types on the wire (swa/dds/naming.h) and the variables that choose them: pure, no DDS.

#include <gtest/gtest.h>

#include <map>
#include <stdexcept>
#include <string>

#include "error_text.h"
#include "fake_env.h"
#include "swa/dds/deployment.h"
#include "swa/dds/naming.h"
#include "swa/dds/topics.h"

namespace swa {
namespace {

using dds::Naming;
using dds::WireNames;

dds::Deployment deploymentOf(const std::map<std::string, std::string>& vars) {
  return dds::parseDeployment(testing::fakeEnv(vars));
}

std::string errorOf(const std::map<std::string, std::string>& vars) {
  return testing::invalidArgumentText([&] { deploymentOf(vars); });
}

TEST(Naming, SwaNamingKeepsTheNamesOfTheCode) {
  // GIVEN the default naming
  const WireNames swa;
  // THEN topics and types go on the wire as the code names them
  EXPECT_EQ(dds::ddsTopic(swa, dds::topics::imu(1)), "swa/uav1/imu");
  EXPECT_EQ(dds::ddsTopic(swa, dds::topics::kTruth), "swa/truth");
  EXPECT_EQ(dds::ddsType(swa, "swa::msg::Imu"), "swa::msg::Imu");
  EXPECT_EQ(dds::swaTopic(swa, "swa/uav1/cmd_vel"), std::optional<std::string>("swa/uav1/cmd_vel"));
  // AND a ROS-mapped name is not one of its topics
  EXPECT_FALSE(dds::swaTopic(swa, "rt/swa/uav1/cmd_vel"));
}

TEST(Naming, Ros2NamingIsTheRosMappingOfCleanRosNames) {
  // GIVEN the ros2 naming without a namespace
  const WireNames ros{Naming::kRos2, ""};
  // THEN every SWA topic is the ROS topic /swa/... mapped with the rt/ prefix
  EXPECT_EQ(dds::ddsTopic(ros, dds::topics::imu(1)), "rt/swa/uav1/imu");
  EXPECT_EQ(dds::ddsTopic(ros, dds::topics::cmdVel(12)), "rt/swa/uav12/cmd_vel");
  EXPECT_EQ(dds::ddsTopic(ros, dds::topics::kClock), "rt/swa/clock");
  // AND every SWA type is swa_msgs/msg/<T> as the rmw names it
  EXPECT_EQ(dds::ddsType(ros, "swa::msg::Imu"), "swa_msgs::msg::dds_::Imu_");
  // AND under either naming a PX4 message in a later release's layout is registered under the name PX4 gives it in
  // every release
  for (const WireNames& n : {WireNames{}, ros}) {
    EXPECT_EQ(dds::ddsType(n, "px4_v1_16::px4_msgs::msg::dds_::VehicleStatus_"), "px4_msgs::msg::dds_::VehicleStatus_");
    EXPECT_EQ(dds::ddsType(n, "px4_msgs::msg::dds_::VehicleStatus_"), "px4_msgs::msg::dds_::VehicleStatus_");
    EXPECT_EQ(dds::ddsType(n, "px4_v1_16::other::T"), "px4_v1_16::other::T");
  }
  EXPECT_EQ(dds::ddsType(ros, "swa::msg::AgentState"), "swa_msgs::msg::dds_::AgentState_");
  EXPECT_EQ(dds::rosTypeOf(dds::ddsType(ros, "swa::msg::Detections")),
            std::optional<std::string>("swa_msgs/msg/Detections"));
  // AND the mapping is undone for the topics it made
  EXPECT_EQ(dds::swaTopic(ros, "rt/swa/uav3/state"), std::optional<std::string>("swa/uav3/state"));
  EXPECT_FALSE(dds::swaTopic(ros, "swa/uav3/state"));
}

TEST(Naming, NamesThatAreDdsNamesAlreadyPassThrough) {
  // GIVEN the ros2 naming with a namespace
  const WireNames ros{Naming::kRos2, "team_a"};
  // THEN PX4's topics and ROS-named types are not renamed again
  EXPECT_EQ(dds::ddsTopic(ros, "rt/px4_1/fmu/in/trajectory_setpoint"), "rt/px4_1/fmu/in/trajectory_setpoint");
  EXPECT_EQ(dds::ddsType(ros, "px4_msgs::msg::dds_::TrajectorySetpoint_"), "px4_msgs::msg::dds_::TrajectorySetpoint_");
  EXPECT_EQ(dds::ddsType(ros, "geometry_msgs::msg::dds_::TwistStamped_"), "geometry_msgs::msg::dds_::TwistStamped_");
  // AND SWA's topics get the namespace, which tells two swarms apart
  EXPECT_EQ(dds::ddsTopic(ros, dds::topics::imu(0)), "rt/team_a/swa/uav0/imu");
  EXPECT_FALSE(dds::swaTopic(ros, "rt/team_b/swa/uav0/imu"));
  EXPECT_FALSE(dds::swaTopic(ros, "rt/swa/uav0/imu"));
  EXPECT_EQ(dds::swaTopic(ros, "rt/team_a/swa/uav0/imu"), std::optional<std::string>("swa/uav0/imu"));
}

TEST(Naming, RosNameRulesAreChecked) {
  // THEN valid ROS topics pass and everything the ROS name rules refuse does not
  EXPECT_TRUE(dds::isValidRosTopic("/swa/uav1/cmd_vel"));
  EXPECT_TRUE(dds::isValidRosTopic("/px4_1/fmu/in/trajectory_setpoint"));
  for (const char* bad :
       {"swa/uav1/imu", "/", "/swa//imu", "/swa/", "/swa/1uav", "/swa/a__b", "/swa/uav-1", "/swa/uäv"}) {
    EXPECT_FALSE(dds::isValidRosTopic(bad)) << bad;
  }
  EXPECT_EQ(dds::rosTopicOf("rt/swa/uav1/imu"), std::optional<std::string>("/swa/uav1/imu"));
  EXPECT_FALSE(dds::rosTopicOf("swa/uav1/imu"));
  // AND ROS type names follow pkg::msg::dds_::Name_
  EXPECT_EQ(dds::rosTypeOf("px4_msgs::msg::dds_::VehicleStatus_"),
            std::optional<std::string>("px4_msgs/msg/VehicleStatus"));
  for (const char* bad : {"swa::msg::Imu", "swa_msgs::msg::dds_::Imu", "swa_msgs::msg::Imu_", "Swa::msg::dds_::Imu_",
                          "swa_msgs::srv::dds_::Imu_", "swa_msgs::msg::dds_::imu_", "swa_msgs:msg::dds_::Imu_"}) {
    EXPECT_FALSE(dds::rosTypeOf(bad)) << bad;
  }
}

TEST(Naming, EnvironmentChoosesTheNaming) {
  // WHEN nothing is set THEN SWA's own names
  EXPECT_EQ(deploymentOf({}).names.naming, Naming::kSwa);
  // WHEN SWA_NAMING=ros2 with a namespace THEN the ROS mapping in that namespace (leading '/' accepted)
  const dds::Deployment d = deploymentOf({{"SWA_NAMING", "ros2"}, {"SWA_ROS_NAMESPACE", "/lab/team_a"}});
  EXPECT_EQ(d.names.naming, Naming::kRos2);
  EXPECT_EQ(d.names.ros_namespace, "lab/team_a");
  EXPECT_EQ(dds::parseNaming(dds::namingName(Naming::kRos2)), Naming::kRos2);
}

TEST(Naming, TwoRosNamespacesAreTwoSwarms) {
  // GIVEN processes of the same SWA_SWARM in two ROS namespaces, and one without
  const dds::Deployment a = deploymentOf({{"SWA_SWARM", "x"}, {"SWA_NAMING", "ros2"}, {"SWA_ROS_NAMESPACE", "a"}});
  const dds::Deployment b = deploymentOf({{"SWA_SWARM", "x"}, {"SWA_NAMING", "ros2"}, {"SWA_ROS_NAMESPACE", "b"}});
  const dds::Deployment plain = deploymentOf({{"SWA_SWARM", "x"}});
  // THEN they are three swarms to each other (an agent of each may run for the same UAV index)
  EXPECT_NE(dds::swarmIdentity(a), dds::swarmIdentity(b));
  EXPECT_NE(dds::swarmIdentity(a), dds::swarmIdentity(plain));
  EXPECT_EQ(dds::swarmIdentity(plain), "x");
  EXPECT_EQ(dds::swarmIdentity(a), "x@/a");
}

TEST(Naming, BadNamingVariablesAreRefusedWithTheVariableNamed) {
  EXPECT_NE(errorOf({{"SWA_NAMING", "ros"}}).find("SWA_NAMING 'ros' is not one of swa, ros2"), std::string::npos);
  // A namespace without the ros2 naming would be silently ignored: refused instead.
  EXPECT_NE(errorOf({{"SWA_ROS_NAMESPACE", "team_a"}}).find("SWA_NAMING is not ros2"), std::string::npos);
  EXPECT_NE(errorOf({{"SWA_NAMING", "ros2"}, {"SWA_ROS_NAMESPACE", "team-a"}}).find("SWA_ROS_NAMESPACE: 'team-a'"),
            std::string::npos);
  EXPECT_NE(errorOf({{"SWA_NAMING", "ros2"}, {"SWA_ROS_NAMESPACE", "a//b"}}).find("empty token"), std::string::npos);
  EXPECT_NE(errorOf({{"SWA_NAMING", "ros2"}, {"SWA_ROS_NAMESPACE", "2nd"}}).find("starting with a digit"),
            std::string::npos);
}

}  // namespace
}  // namespace swa

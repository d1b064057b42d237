#pragma once
// What SWA's topics and types are called on the wire (deploy/README.md, "ROS 2 profile"). The code names every topic
// by its SWA name (swa/dds/topics.h: swa/uav1/imu) and every type by its generated name (swa::msg::Imu); this is the
// one place that turns them into DDS names. No DDS include: the rules are tested on their own.
//
//   SWA_NAMING=swa (default)  topic swa/uav1/imu,            type swa::msg::Imu
//   SWA_NAMING=ros2           topic rt[/<ns>]/swa/uav1/imu,  type swa_msgs::msg::dds_::Imu_
//                             (ROS 2's mapping of the ROS topic /<ns>/swa/uav1/imu and the ROS type swa_msgs/msg/Imu,
//                             as rmw_fastrtps and rmw_cyclonedds write them; ROS tools see only topics under rt/)
//   SWA_ROS_NAMESPACE=NS      ros2 only: a ROS namespace in front of every SWA topic, so two swarms can share a domain
//
// Topics that are not SWA's (PX4's rt/<vehicle>/fmu/...) and types generated with ROS names already (px4_msgs,
// geometry_msgs) are DDS names to begin with and pass through unchanged. The payload encoding is XCDR1 (classic CDR)
// in both namings, which is what every ROS 2 rmw uses.

#include <optional>
#include <string>

namespace swa::dds {

enum class Naming { kSwa, kRos2 };

struct WireNames {
  Naming naming = Naming::kSwa;
  std::string ros_namespace;  // without leading or trailing '/', e.g. "team_a" or "lab/team_a"; ros2 only
};

const char* namingName(Naming n);
std::optional<Naming> parseNaming(const std::string& name);

// Why `ns` is not a usable ROS namespace (tokens of letters, digits and '_' separated by '/', not starting with a
// digit, no "__", no empty token; one leading '/' allowed), if it is not.
std::optional<std::string> rosNamespaceProblem(const std::string& ns);
// `ns` without its leading '/' (call after rosNamespaceProblem found none).
std::string normalRosNamespace(const std::string& ns);

// Whether `topic` is one of SWA's own topics (under swa/), which the naming renames.
bool isSwaTopic(const std::string& topic);

// The DDS topic of `topic` (an SWA name, or a DDS name that passes through).
std::string ddsTopic(const WireNames& names, const std::string& topic);
// The SWA name of a DDS topic of this naming; nullopt if it is not one of SWA's topics under this naming.
std::optional<std::string> swaTopic(const WireNames& names, const std::string& dds_topic);

// The DDS type name of a generated type name: under ros2, swa::msg::<T> is swa_msgs::msg::dds_::<T>_; a PX4 type of a
// later release's layout, px4_v1_16::px4_msgs::msg::dds_::<T>_ (idl/px4), is px4_msgs::msg::dds_::<T>_ under either
// naming, as PX4 names it in every release; every other name (a ROS-named type already) passes through.
std::string ddsType(const WireNames& names, const std::string& generated_type);

// The ROS 2 topic a DDS topic stands for ("rt/swa/uav1/imu" -> "/swa/uav1/imu"), if it is under rt/.
std::optional<std::string> rosTopicOf(const std::string& dds_topic);
// Whether `name` is a valid fully qualified ROS 2 topic name ("/a/b_c": tokens as in rosNamespaceProblem).
bool isValidRosTopic(const std::string& name);
// The ROS 2 type a DDS type name stands for ("pkg::msg::dds_::T_" -> "pkg/msg/T"), if it follows the ROS mapping.
std::optional<std::string> rosTypeOf(const std::string& dds_type);

}  // namespace swa::dds

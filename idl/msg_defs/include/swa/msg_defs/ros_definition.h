#pragma once
// SWA's message definitions as ROS 2 tools want them, without ROS: the text of each .msg file of swa_msgs, and the
// "concatenated" definition rosbag2 stores per topic (the message's own .msg, then every type it uses, once, depth
// first, each after a line of 80 '=' and "MSG: swa_msgs/<Type>"). An MCAP channel with schema encoding "ros2msg"
// carries the latter; Foxglove, Lichtblick and PlotJuggler decode the CDR payloads with it.

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace swa::msg_defs {

constexpr const char* kPackage = "swa_msgs";

// Every message of swa_msgs ("AgentState", "Detection", ...), sorted.
std::vector<std::string> typeNames();
// The .msg file of `type`; nullopt if swa_msgs has none.
std::optional<std::string_view> msgText(std::string_view type);
// The ROS 2 type name of `type`: "swa_msgs/msg/Imu".
std::string rosTypeName(std::string_view type);
// The concatenated definition of `type`; nullopt if swa_msgs has no such message. Throws std::logic_error if a field
// names a type that is neither a ROS primitive nor a message of swa_msgs (the lock-step test keeps that from
// happening).
std::optional<std::string> rosDefinition(std::string_view type);

}  // namespace swa::msg_defs

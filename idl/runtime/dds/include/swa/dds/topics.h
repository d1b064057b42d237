#pragma once
// Topic names of the SWA system (DESIGN §1). Per-UAV topics carry the UAV index in the name so DDS Security
// permissions can be written per UAV: agent i may read only swa/uav<i>/{detections,imu,gnss,sensors} and write only
// swa/uav<i>/{cmd_vel,state}. The monitor-only topics are global, and so is the ground's mission, which every agent
// reads.

#include <string>

namespace swa::dds::topics {

inline std::string uavPrefix(int uav) { return "swa/uav" + std::to_string(uav) + "/"; }

inline std::string detections(int uav) { return uavPrefix(uav) + "detections"; }
// Detections as real detectors publish them (agent sensor.input), DDS names of the ROS topics /uav<i>/detections
// (vision_msgs/Detection3DArray) and /uav<i>/uvdar/measuredPoses (UVDAR's convention). ROS names already: the naming of
// SWA_NAMING does not apply to them.
inline std::string visionDetections(int uav) { return "rt/uav" + std::to_string(uav) + "/detections"; }
inline std::string uvdarPoses(int uav) { return "rt/uav" + std::to_string(uav) + "/uvdar/measuredPoses"; }
inline std::string imu(int uav) { return uavPrefix(uav) + "imu"; }
inline std::string gnss(int uav) { return uavPrefix(uav) + "gnss"; }
// A simulator step's imu, detections and gnss in one message (idl/SensorFrame.idl), SWA naming only.
inline std::string sensors(int uav) { return uavPrefix(uav) + "sensors"; }
inline std::string cmdVel(int uav) { return uavPrefix(uav) + "cmd_vel"; }
// The same setpoint as geometry_msgs/TwistStamped, written only in the ros2 naming (swa/dds/naming.h).
inline std::string cmdVelStamped(int uav) { return uavPrefix(uav) + "cmd_vel_stamped"; }
inline std::string state(int uav) { return uavPrefix(uav) + "state"; }

// Diagnostics of UAV <i>'s autopilot bridge (swa_px4_bridge).
inline std::string bridgeState(int uav) { return uavPrefix(uav) + "bridge_state"; }

inline const char* const kTruth = "swa/truth";
inline const char* const kEvents = "swa/events";
inline const char* const kClock = "swa/clock";
// The ground's swarm mission (issue #45): written by the ground station (swa_mission) only, read by every agent and
// the monitor. The same for every UAV, and no UAV's state goes into it: not communication between agents.
inline const char* const kMission = "swa/swarm/mission";

// PX4's uXRCE-DDS topics of the vehicle with ROS namespace `ns` (empty: none): rt/<ns>/fmu/<in|out>/<name>. DDS names
// already (the naming of SWA_NAMING does not apply to them). `name` is the release's topic name: from v1.16 a
// versioned message's carries its version (swa/px4/release.h: topicName).
inline std::string px4In(const std::string& ns, const std::string& name) {
  return "rt/" + (ns.empty() ? std::string() : ns + "/") + "fmu/in/" + name;
}
inline std::string px4Out(const std::string& ns, const std::string& name) {
  return "rt/" + (ns.empty() ? std::string() : ns + "/") + "fmu/out/" + name;
}
// The namespace swa_sim's PX4 stand-in gives UAV <i>, and swa_px4_bridge --id <i> assumes unless told: px4_<i>.
inline std::string px4Namespace(int uav) { return "px4_" + std::to_string(uav); }

// ArduPilot's (AP_DDS) topics rt/<ns>/<name> and its services as ROS 2 puts them on DDS: requests on
// rq/<ns>/<name>Request, replies on rr/<ns>/<name>Reply.
inline std::string apTopic(const std::string& ns, const std::string& name) { return "rt/" + ns + "/" + name; }
inline std::string apRequest(const std::string& ns, const std::string& name) {
  return "rq/" + ns + "/" + name + "Request";
}
inline std::string apReply(const std::string& ns, const std::string& name) { return "rr/" + ns + "/" + name + "Reply"; }
// The namespace swa_sim's ArduPilot stand-in gives UAV <i>, and swa_px4_bridge --autopilot ardupilot --id <i> assumes
// unless told: ap/v<i+1>, where AP_DDS puts a vehicle's topics with DDS_USE_NS = 1 and MAV_SYSID = i + 1.
inline std::string apNamespace(int uav) { return "ap/v" + std::to_string(uav + 1); }

}  // namespace swa::dds::topics

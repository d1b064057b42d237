#pragma once
// The QoS profiles of idl/runtime/dds/profiles.xml by name, the one place a profile name is written in C++: a typo
// here fails the build, not a discovery at run time (Fast DDS 2.9 falls back to its defaults for an unknown profile and
// only logs). tests/layers/check_qos_names.py keeps this list and the XML the same, and finds any literal elsewhere.
// What each profile does, and why, is said beside it in profiles.xml.

namespace swa::dds::qos {

// Participants (swa/dds/deployment.h picks one by SWA_TRANSPORT).
inline constexpr const char* kParticipant = "swa_participant";
inline constexpr const char* kParticipantNetwork = "swa_participant_network";

// Sensors, simulator -> agent. The _realtime writers repair a lost sample within 20 ms instead of 100 ms.
inline constexpr const char* kSensorWriter = "swa_sensor_writer";
inline constexpr const char* kSensorWriterRealtime = "swa_sensor_writer_realtime";
inline constexpr const char* kSensorReader = "swa_sensor_reader";
inline constexpr const char* kDetectionsGnssWriter = "swa_detections_gnss_writer";
inline constexpr const char* kDetectionsGnssReader = "swa_detections_gnss_reader";
inline constexpr const char* kFrameWriter = "swa_frame_writer";
inline constexpr const char* kFrameWriterRealtime = "swa_frame_writer_realtime";
inline constexpr const char* kFrameReader = "swa_frame_reader";

// A real detector's output, and a ROS 2 node's default publisher (what such a detector uses).
inline constexpr const char* kForeignDetectionsReader = "foreign_detections_reader";
inline constexpr const char* kRos2DefaultWriter = "ros2_default_writer";

// Velocity setpoints, agent -> simulator or bridge.
inline constexpr const char* kCommandWriter = "swa_command_writer";
inline constexpr const char* kCommandReader = "swa_command_reader";

// Diagnostics and the monitor's inputs.
inline constexpr const char* kStateWriter = "swa_state_writer";
inline constexpr const char* kStateReader = "swa_state_reader";
inline constexpr const char* kTruthWriter = "swa_truth_writer";
inline constexpr const char* kTruthReader = "swa_truth_reader";
inline constexpr const char* kEventWriter = "swa_event_writer";
inline constexpr const char* kEventReader = "swa_event_reader";

// The ground's mission, and the simulation clock (the agent's watch reader only listens for a repeated tick).
inline constexpr const char* kMissionWriter = "swa_mission_writer";
inline constexpr const char* kMissionReader = "swa_mission_reader";
inline constexpr const char* kClockWriter = "swa_clock_writer";
inline constexpr const char* kClockReader = "swa_clock_reader";
inline constexpr const char* kClockWatchReader = "swa_clock_watch_reader";

// PX4's uXRCE-DDS topics (fmu/out, fmu/in), with the QoS PX4's client gives them.
inline constexpr const char* kPx4OutWriter = "px4_out_writer";
inline constexpr const char* kPx4OutReader = "px4_out_reader";
inline constexpr const char* kPx4InWriter = "px4_in_writer";
inline constexpr const char* kPx4InReader = "px4_in_reader";

// ArduPilot's AP_DDS topics and services, with the QoS of its XRCE-DDS profiles.
inline constexpr const char* kApOutWriter = "ap_out_writer";
inline constexpr const char* kApOutReader = "ap_out_reader";
inline constexpr const char* kApStatusWriter = "ap_status_writer";
inline constexpr const char* kApStatusReader = "ap_status_reader";
inline constexpr const char* kApInWriter = "ap_in_writer";
inline constexpr const char* kApInReader = "ap_in_reader";
inline constexpr const char* kApServiceWriter = "ap_service_writer";
inline constexpr const char* kApServiceReader = "ap_service_reader";

}  // namespace swa::dds::qos

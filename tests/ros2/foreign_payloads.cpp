// The payloads of the other systems' messages SWA speaks (issue #27), for the independent decoder
// (test_foreign_decode.sh, decoder/foreign_check.mjs):
//   foreign_payloads write FILE   every type's payload as SWA's generated code serialises it, with the values set
//   foreign_payloads check FILE   payloads the independent implementation serialised, deserialised here and compared
// Types: vision_msgs/Detection3DArray and mrs_msgs/PoseWithCovarianceArrayStamped (as the simulator writes them and
// the agent reads them), PX4's VehicleStatus, SensorGps and VehicleLocalPosition in every release's layout (as the
// stand-in writes them and the bridge reads them), and ArduPilot's sensor_msgs/Imu and NavSatFix,
// ardupilot_msgs/Status, cmd_vel (geometry_msgs/TwistStamped) and the arm_motors / mode_switch requests and responses
// (both ways: the stand-in and the bridge each write some and read the others). Exit 0 when everything matched, 1
// otherwise, 2 on bad usage.

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include <swa/px4/SensorGps_v1_15PubSubTypes.h>
#include <swa/px4/SensorGps_v1_17PubSubTypes.h>
#include <swa/px4/VehicleLocalPosition_v1_15PubSubTypes.h>
#include <swa/px4/VehicleLocalPosition_v1_16PubSubTypes.h>
#include <swa/px4/VehicleOdometry_v1_15PubSubTypes.h>
#include <swa/px4/VehicleStatus_v1_15PubSubTypes.h>
#include <swa/px4/VehicleStatus_v1_16PubSubTypes.h>
#include <swa/ros/ArdupilotServicesPubSubTypes.h>
#include <swa/ros/ArdupilotStatusPubSubTypes.h>
#include <swa/ros/Detection3DArrayPubSubTypes.h>
#include <swa/ros/ImuPubSubTypes.h>
#include <swa/ros/NavSatFixPubSubTypes.h>
#include <swa/ros/PoseWithCovarianceArrayStampedPubSubTypes.h>
#include <swa/ros/TFMessagePubSubTypes.h>
#include <swa/ros/TwistStampedPubSubTypes.h>

#include "swa/wire/ardupilot.h"
#include "swa/wire/px4.h"
#include "swa/wire/ros_detections.h"

namespace {

using json = nlohmann::json;

std::string hexOf(const std::vector<std::uint8_t>& bytes) {
  static const char* digits = "0123456789abcdef";
  std::string s;
  for (const std::uint8_t b : bytes) {
    s += digits[b >> 4];
    s += digits[b & 15];
  }
  return s;
}

std::vector<std::uint8_t> bytesOf(const std::string& hex) {
  std::vector<std::uint8_t> b;
  for (std::size_t k = 0; k + 1 < hex.size(); k += 2)
    b.push_back(static_cast<std::uint8_t>(std::stoi(hex.substr(k, 2), nullptr, 16)));
  return b;
}

template <class PubSubType>
std::string serialise(typename PubSubType::type m) {
  PubSubType type;
  eprosima::fastrtps::rtps::SerializedPayload_t p(type.getSerializedSizeProvider(&m)());
  if (!type.serialize(&m, &p)) throw std::runtime_error("cannot serialise " + std::string(type.getName()));
  return hexOf(std::vector<std::uint8_t>(p.data, p.data + p.length));
}

template <class PubSubType>
typename PubSubType::type deserialise(const std::string& hex) {
  const std::vector<std::uint8_t> b = bytesOf(hex);
  eprosima::fastrtps::rtps::SerializedPayload_t p(static_cast<std::uint32_t>(b.size()));
  std::copy(b.begin(), b.end(), p.data);
  p.length = static_cast<std::uint32_t>(b.size());
  PubSubType type;
  typename PubSubType::type m;
  if (!type.deserialize(&p, &m)) throw std::runtime_error("cannot deserialise " + std::string(type.getName()));
  return m;
}

// Three detections: identified with a covariance, identified without one, anonymous.
swa::agent::DetectionSet detectionSet() {
  swa::agent::DetectionSet s;
  s.stamp_ns = 12'345'678'901LL;
  swa::agent::Detection a;
  a.target_id = 4;
  a.position_body_m = swa::agent::Vec2(9.5, -1.25);
  swa::agent::Mat2 c;
  c << 0.04, 0.005, 0.005, 0.09;
  a.covariance_m2 = c;
  swa::agent::Detection b;
  b.target_id = 7;
  b.position_body_m = swa::agent::Vec2(-3.0, 8.0);
  swa::agent::Detection anon;
  anon.position_body_m = swa::agent::Vec2(0.5, 10.0);
  s.detections = {a, b, anon};
  return s;
}

swa::agent::GnssSample gnss() {
  swa::agent::GnssSample g;
  g.stamp_ns = 42'000'000'000LL;
  g.valid = true;
  g.position_m = swa::agent::Vec2(12.5, -7.25);
  g.std_m = 0.75;
  return g;
}

json header(const std::string& frame) {
  return {{"stamp", {{"sec", 12}, {"nanosec", 345678901}}}, {"frame_id", frame}};
}

json covarianceJson(bool with) {
  json c = json::array();
  for (int k = 0; k < 36; ++k) c.push_back(0.0);
  if (with) {
    c[0] = 0.04;
    c[1] = 0.005;
    c[6] = 0.005;
    c[7] = 0.09;
  }
  return c;
}

json pose(double x, double y) {
  return {{"position", {{"x", x}, {"y", y}, {"z", 0.0}}},
          {"orientation", {{"x", 0.0}, {"y", 0.0}, {"z", 0.0}, {"w", 1.0}}}};
}

// What SWA's writer puts in every field (complete: the decoder must give exactly this).
json visionExpected() {
  json dets = json::array();
  const std::vector<std::tuple<double, double, bool, std::string>> rows = {
      {9.5, -1.25, true, "4"}, {-3.0, 8.0, false, "7"}, {0.5, 10.0, false, ""}};
  for (const auto& [x, y, cov, id] : rows) {
    const json p = pose(x, y);
    dets.push_back({{"header", header("uav3/fcu")},
                    {"results", json::array({{{"hypothesis", {{"class_id", "uav"}, {"score", 1.0}}},
                                              {"pose", {{"pose", p}, {"covariance", covarianceJson(cov)}}}}})},
                    {"bbox", {{"center", p}, {"size", {{"x", 0.0}, {"y", 0.0}, {"z", 0.0}}}}},
                    {"id", id}});
  }
  return {{"header", header("uav3/fcu")}, {"detections", dets}};
}

json uvdarExpected() {
  json poses = json::array();
  // The ids as decimal strings: a 64-bit integer (upstream's uint64 id) has no exact JSON number.
  const std::vector<std::tuple<double, double, bool, std::uint64_t>> rows = {
      {9.5, -1.25, true, 4u}, {-3.0, 8.0, false, 7u}, {0.5, 10.0, false, swa::wire::kUvdarNoId}};
  for (const auto& [x, y, cov, id] : rows) {
    poses.push_back({{"id", std::to_string(id)}, {"pose", pose(x, y)}, {"covariance", covarianceJson(cov)}});
  }
  return {{"header", header("uav3/fcu")}, {"poses", poses}};
}

// ArduPilot: an attitude heading 30 deg east of north, 5 deg nose up, at 12.345678 s; the agent's command 1.5 m/s east,
// -0.5 m/s north, turning at 0.25 rad/s, answering that sample.
namespace ap {

constexpr std::uint64_t kStampUs = 12'345'678;
const swa::px4::Quaternion kAttitude =
    swa::px4::quaternionOf(swa::px4::Euler{0.0, 5.0 * M_PI / 180.0, 30.0 * M_PI / 180.0});

swa::autopilot::Setpoint setpoint() {
  return swa::autopilot::Setpoint{kStampUs, swa::px4::nedOf(swa::agent::Vec2(1.5, -0.5)), swa::px4::yawspeedOf(0.25)};
}

json time() { return {{"sec", 12}, {"nanosec", 345678000}}; }
json vector3(double x, double y, double z) { return {{"x", x}, {"y", y}, {"z", z}}; }
json nine(double first) {
  json a = json::array({first});
  for (int k = 1; k < 9; ++k) a.push_back(0.0);
  return a;
}

json imuExpected() {
  const swa::ardupilot::OrientationFields q = swa::ardupilot::orientationFieldsOf(kAttitude);
  const swa::ardupilot::SpecificForce f = swa::ardupilot::restingForceOf(kAttitude);
  return {{"header", {{"stamp", time()}, {"frame_id", "base_link_ned"}}},
          {"orientation", {{"x", q.x}, {"y", q.y}, {"z", q.z}, {"w", q.w}}},
          {"orientation_covariance", nine(0.0)},
          {"angular_velocity", vector3(0, 0, 0)},
          {"angular_velocity_covariance", nine(-1.0)},
          {"linear_acceleration", vector3(f.x, f.y, f.z)},
          {"linear_acceleration_covariance", nine(0.0)}};
}

json statusExpected() {
  return {{"header", {{"stamp", time()}, {"frame_id", ""}}},
          {"vehicle_type", 2},
          {"armed", true},
          {"mode", 4},
          {"flying", true},
          {"external_control", true},
          {"failsafe", json::array({24})}};
}

json navSatExpected() {
  json cov = json::array({0.5625, 0.0, 0.0, 0.0, 0.5625, 0.0, 0.0, 0.0, 2.25});
  return {{"header", {{"stamp", time()}, {"frame_id", "0"}}},
          {"status", {{"status", 0}, {"service", 1}}},
          {"latitude", 47.397742},
          {"longitude", 8.545594},
          {"altitude", 0.0},
          {"position_covariance", cov},
          {"position_covariance_type", 2}};
}

json cmdVelExpected() {
  return {{"header", {{"stamp", time()}, {"frame_id", "map"}}},
          {"twist", {{"linear", vector3(1.5, -0.5, 0.0)}, {"angular", vector3(0.0, 0.0, 0.25)}}}};
}

// External odometry (issue #43): the agent's estimate as the bridge writes it. PX4: every field set to a distinct
// finite value (the bridge's own leaves q NaN, which JSON cannot carry), so that the whole layout is compared.
swa::autopilot::Odometry odometry() {
  swa::autopilot::Odometry o;
  o.stamp_ns = 12'345'678'000;
  o.position_m = swa::agent::Vec2(3.0, -4.0);
  o.velocity_mps = swa::agent::Vec2(0.5, 0.25);
  o.position_var_m2 = swa::agent::Vec2(0.25, 0.125);
  o.velocity_var_m2ps2 = swa::agent::Vec2(0.0625, 0.03125);
  o.reset_counter = 3;
  return o;
}

px4_msgs::msg::VehicleOdometry px4Odometry() {
  px4_msgs::msg::VehicleOdometry m = swa::wire::vehicleOdometry(odometry());
  m.timestamp(42'000'001);
  m.q({0.5f, 0.5f, -0.5f, 0.5f});
  m.angular_velocity({0.125f, -0.25f, 0.375f});
  m.orientation_variance({0.01171875f, 0.0234375f, 0.046875f});
  m.quality(-7);
  return m;
}

json px4OdometryExpected() {
  return {{"timestamp", "42000001"},
          {"timestamp_sample", "12345678"},
          {"pose_frame", 1},
          {"position", {-4.0, 3.0, 0.0}},
          {"q", {0.5, 0.5, -0.5, 0.5}},
          {"velocity_frame", 1},
          {"velocity", {0.25, 0.5, 0.0}},
          {"angular_velocity", {0.125, -0.25, 0.375}},
          {"position_variance", {0.125, 0.25, 10000.0}},
          {"orientation_variance", {0.01171875, 0.0234375, 0.046875}},
          {"velocity_variance", {0.03125, 0.0625, 10000.0}},
          {"reset_counter", 3},
          {"quality", -7}};
}

const swa::px4::Quaternion kOdomAttitude{0.5, 0.5, 0.5, 0.5};

json tfExpected() {
  return {{"transforms", json::array({{{"header", {{"stamp", {{"sec", 0}, {"nanosec", 0}}}, {"frame_id", "odom"}}},
                                       {"child_frame_id", "base_link"},
                                       {"transform",
                                        {{"translation", ap::vector3(-4.0, -3.0, 0.0)},
                                         {"rotation", {{"x", 0.5}, {"y", -0.5}, {"z", -0.5}, {"w", 0.5}}}}}}})}};
}

}  // namespace ap

int write(const std::string& path) {
  namespace px4 = px4_msgs::msg;
  namespace px4_16 = px4_v1_16::px4_msgs::msg;
  namespace px4_17 = px4_v1_17::px4_msgs::msg;
  const swa::agent::DetectionSet s = detectionSet();
  const swa::agent::GnssSample g = gnss();
  json out = json::array();
  out.push_back(
      {{"ros_type", "vision_msgs/msg/Detection3DArray"},
       {"cdr_hex", serialise<vision_msgs::msg::Detection3DArrayPubSubType>(swa::wire::detection3DArray(s, 3))},
       {"expected", visionExpected()}});
  out.push_back(
      {{"ros_type", "mrs_msgs/msg/PoseWithCovarianceArrayStamped"},
       {"cdr_hex", serialise<mrs_msgs::msg::PoseWithCovarianceArrayStampedPubSubType>(swa::wire::poseArray(s, 3))},
       {"expected", uvdarExpected()}});
  // PX4: the fields the stand-in sets; every other field must decode as zero (`zero_elsewhere`).
  const json status = {{"timestamp", "42000000"},
                       {"arming_state", 2},
                       {"nav_state", 14},
                       {"nav_state_user_intention", 14},
                       {"nav_state_timestamp", "42000000"},
                       {"failsafe", true},
                       {"vehicle_type", 1},
                       {"system_id", 4},
                       {"component_id", 1},
                       {"pre_flight_checks_pass", true}};
  const auto addPx4 = [&](const std::string& tag, const std::string& name, const std::string& hex, json expected) {
    out.push_back({{"ros_type", "px4_msgs/msg/" + name},
                   {"px4_release", tag},
                   {"cdr_hex", hex},
                   {"expected", std::move(expected)},
                   {"zero_elsewhere", true}});
  };
  const std::uint64_t t = 42'000'000;
  addPx4("v1.15.4", "VehicleStatus",
         serialise<px4::VehicleStatusPubSubType>(swa::wire::vehicleStatus<px4::VehicleStatus>(t, 2, 14, true, 4)),
         status);
  for (const char* tag : {"v1.16.0", "v1.17.0"}) {
    addPx4(
        tag, "VehicleStatus",
        serialise<px4_16::VehicleStatusPubSubType>(swa::wire::vehicleStatus<px4_16::VehicleStatus>(t, 2, 14, true, 4)),
        status);
  }
  const json gps = {{"timestamp", "42000000"},
                    {"timestamp_sample", "42000000"},
                    {"fix_type", 3},
                    {"satellites_used", 10},
                    {"eph", 0.75},
                    {"epv", 1.5}};
  for (const char* tag : {"v1.15.4", "v1.16.0"}) {
    addPx4(tag, "SensorGps", serialise<px4::SensorGpsPubSubType>(swa::wire::sensorGps<px4::SensorGps>(t, g)), gps);
  }
  addPx4("v1.17.0", "SensorGps", serialise<px4_17::SensorGpsPubSubType>(swa::wire::sensorGps<px4_17::SensorGps>(t, g)),
         gps);
  const json position = {{"timestamp", "42000000"},
                         {"timestamp_sample", "42000000"},
                         {"xy_valid", true},
                         {"v_xy_valid", true},
                         {"x", -7.25},
                         {"y", 12.5},
                         {"eph", 0.75}};
  addPx4(
      "v1.15.4", "VehicleLocalPosition",
      serialise<px4::VehicleLocalPositionPubSubType>(swa::wire::vehicleLocalPosition<px4::VehicleLocalPosition>(t, g)),
      position);
  for (const char* tag : {"v1.16.0", "v1.17.0"}) {
    addPx4(tag, "VehicleLocalPosition",
           serialise<px4_16::VehicleLocalPositionPubSubType>(
               swa::wire::vehicleLocalPosition<px4_16::VehicleLocalPosition>(t, g)),
           position);
  }
  for (const char* tag : {"v1.15.4", "v1.16.0", "v1.17.0"}) {  // one layout in all three
    out.push_back({{"ros_type", "px4_msgs/msg/VehicleOdometry"},
                   {"px4_release", tag},
                   {"cdr_hex", serialise<px4::VehicleOdometryPubSubType>(ap::px4Odometry())},
                   {"expected", ap::px4OdometryExpected()},
                   {"zero_elsewhere", true}});
  }
  // ArduPilot's, complete: the decoder must give exactly these.
  namespace srv = ardupilot_msgs::srv;
  out.push_back({{"ros_type", "tf2_msgs/msg/TFMessage"},
                 {"cdr_hex", serialise<tf2_msgs::msg::TFMessagePubSubType>(
                                 swa::wire::externalOdometry(ap::odometry(), ap::kOdomAttitude))},
                 {"expected", ap::tfExpected()}});
  out.push_back(
      {{"ros_type", "sensor_msgs/msg/Imu"},
       {"cdr_hex", serialise<sensor_msgs::msg::ImuPubSubType>(swa::wire::imuMessage(ap::kStampUs, ap::kAttitude))},
       {"expected", ap::imuExpected()}});
  out.push_back({{"ros_type", "ardupilot_msgs/msg/Status"},
                 {"cdr_hex", serialise<ardupilot_msgs::msg::StatusPubSubType>(
                                 swa::wire::statusMessage(ap::kStampUs, true, 4, true))},
                 {"expected", ap::statusExpected()}});
  out.push_back({{"ros_type", "sensor_msgs/msg/NavSatFix"},
                 {"cdr_hex", serialise<sensor_msgs::msg::NavSatFixPubSubType>(
                                 swa::wire::navSatFix(ap::kStampUs, 47.397742, 8.545594, 0.75))},
                 {"expected", ap::navSatExpected()}});
  out.push_back({{"ros_type", "geometry_msgs/msg/TwistStamped"},
                 {"cdr_hex", serialise<geometry_msgs::msg::TwistStampedPubSubType>(swa::wire::cmdVel(ap::setpoint()))},
                 {"expected", ap::cmdVelExpected()}});
  srv::ArmMotors_Request arm;
  arm.arm(true);
  out.push_back({{"ros_type", "ardupilot_msgs/srv/ArmMotors_Request"},
                 {"cdr_hex", serialise<srv::ArmMotors_RequestPubSubType>(arm)},
                 {"expected", {{"arm", true}}}});
  srv::ArmMotors_Response armed;
  armed.result(true);
  out.push_back({{"ros_type", "ardupilot_msgs/srv/ArmMotors_Response"},
                 {"cdr_hex", serialise<srv::ArmMotors_ResponsePubSubType>(armed)},
                 {"expected", {{"result", true}}}});
  srv::ModeSwitch_Request mode;
  mode.mode(4);
  out.push_back({{"ros_type", "ardupilot_msgs/srv/ModeSwitch_Request"},
                 {"cdr_hex", serialise<srv::ModeSwitch_RequestPubSubType>(mode)},
                 {"expected", {{"mode", 4}}}});
  srv::ModeSwitch_Response switched;
  switched.status(true);
  switched.curr_mode(4);
  out.push_back({{"ros_type", "ardupilot_msgs/srv/ModeSwitch_Response"},
                 {"cdr_hex", serialise<srv::ModeSwitch_ResponsePubSubType>(switched)},
                 {"expected", {{"status", true}, {"curr_mode", 4}}}});
  std::ofstream(path) << out.dump(1) << "\n";
  std::cout << "foreign_payloads: wrote " << out.size() << " payloads to " << path << "\n";
  return 0;
}

// An ArduPilot payload the independent implementation serialised, read as the bridge (Imu, Status, the responses) or
// the stand-in (cmd_vel, the requests) reads it: whether it holds the values written. nullopt: not ArduPilot's.
std::optional<bool> checkArdupilot(const std::string& type, const std::string& hex) {
  namespace srv = ardupilot_msgs::srv;
  if (type == "sensor_msgs/msg/Imu") {
    const sensor_msgs::msg::Imu m = deserialise<sensor_msgs::msg::ImuPubSubType>(hex);
    const swa::px4::Quaternion q = swa::wire::attitudeOf(m, swa::ardupilot::QuaternionLayout::kRos);
    return swa::wire::timestampUsOf(m.header().stamp()) == ap::kStampUs && q.w == ap::kAttitude.w &&
           q.x == ap::kAttitude.x && q.y == ap::kAttitude.y && q.z == ap::kAttitude.z &&
           m.header().frame_id() == "base_link_ned";
  }
  if (type == "ardupilot_msgs/msg/Status") {
    const ardupilot_msgs::msg::Status m = deserialise<ardupilot_msgs::msg::StatusPubSubType>(hex);
    return m.armed() && m.mode() == 4 && m.vehicle_type() == 2 && m.flying() && m.external_control() &&
           m.failsafe() == std::vector<std::uint8_t>{24};
  }
  if (type == "sensor_msgs/msg/NavSatFix") {
    const swa::ardupilot::NavSatReport r =
        swa::wire::navSatReportOf(deserialise<sensor_msgs::msg::NavSatFixPubSubType>(hex));
    return r.timestamp_us == ap::kStampUs && r.status == 0 && r.latitude_deg == 47.397742 &&
           r.longitude_deg == 8.545594 && r.covariance_type == 2 && r.variance_east_m2 == 0.5625 &&
           r.variance_north_m2 == 0.5625;
  }
  if (type == "geometry_msgs/msg/TwistStamped") {
    const swa::wire::CmdVel c = swa::wire::cmdVelOf(deserialise<geometry_msgs::msg::TwistStampedPubSubType>(hex));
    return c.map_frame && c.timestamp_us == ap::kStampUs && c.twist.east_mps == 1.5 && c.twist.north_mps == -0.5 &&
           c.twist.up_mps == 0.0 && c.twist.yaw_rate_radps == 0.25;
  }
  if (type == "tf2_msgs/msg/TFMessage") {
    const std::optional<swa::wire::ExternalOdomReport> r =
        swa::wire::externalOdomOf(deserialise<tf2_msgs::msg::TFMessagePubSubType>(hex));
    return r && r->stamp_ns == 0 && r->north_m == -4.0 && r->east_m == 3.0;
  }
  if (type == "ardupilot_msgs/srv/ArmMotors_Request") return deserialise<srv::ArmMotors_RequestPubSubType>(hex).arm();
  if (type == "ardupilot_msgs/srv/ArmMotors_Response") {
    return deserialise<srv::ArmMotors_ResponsePubSubType>(hex).result();
  }
  if (type == "ardupilot_msgs/srv/ModeSwitch_Request") {
    return deserialise<srv::ModeSwitch_RequestPubSubType>(hex).mode() == 4;
  }
  if (type == "ardupilot_msgs/srv/ModeSwitch_Response") {
    const srv::ModeSwitch_Response m = deserialise<srv::ModeSwitch_ResponsePubSubType>(hex);
    return m.status() && m.curr_mode() == 4;
  }
  return std::nullopt;
}

// Payloads the independent implementation serialised from the same values: read back as the agent reads them.
int check(const std::string& path) {
  std::ifstream in(path);
  const json entries = json::parse(in);
  int failures = 0, checked = 0;
  const auto expectSet = [&](const swa::agent::ForeignDetectionSet& f, const std::string& what) {
    const swa::agent::DetectionSet s = detectionSet();
    bool ok = f.sec == 12 && f.nanosec == 345678901u && f.frame_id == "uav3/fcu" && f.detections.size() == 3;
    for (std::size_t k = 0; ok && k < 3; ++k) {
      ok = f.detections[k].x_m == s.detections[k].position_body_m.x() &&
           f.detections[k].y_m == s.detections[k].position_body_m.y();
    }
    ok = ok && f.detections[0].covariance && (*f.detections[0].covariance)[1] == 0.005 &&
         (*f.detections[0].covariance)[7] == 0.09 && f.detections[0].id == 4 && f.detections[1].id == 7;
    if (!ok) {
      std::cerr << "MISMATCH: " << what << " serialised by the independent implementation reads differently\n";
      ++failures;
    }
    ++checked;
  };
  for (const json& e : entries) {
    const std::string type = e.at("ros_type");
    const std::string hex = e.at("cdr_hex");
    try {
      if (type == "vision_msgs/msg/Detection3DArray") {
        const swa::agent::ForeignDetectionSet f =
            swa::wire::foreignOf(deserialise<vision_msgs::msg::Detection3DArrayPubSubType>(hex));
        expectSet(f, type);
        if (f.detections[2].id) {
          std::cerr << "MISMATCH: the anonymous Detection3D read with an id\n";
          ++failures;
        }
      } else if (type == "mrs_msgs/msg/PoseWithCovarianceArrayStamped") {
        const swa::agent::ForeignDetectionSet f =
            swa::wire::foreignOf(deserialise<mrs_msgs::msg::PoseWithCovarianceArrayStampedPubSubType>(hex));
        expectSet(f, type);
        if (f.detections[2].id) {
          std::cerr << "MISMATCH: the anonymous UVDAR pose (id " << swa::wire::kUvdarNoId << ") read with an id\n";
          ++failures;
        }
      } else if (const std::optional<bool> ok = checkArdupilot(type, hex)) {
        if (!*ok) {
          std::cerr << "MISMATCH: " << type << " serialised by the independent implementation reads differently\n";
          ++failures;
        }
        ++checked;
      } else {
        std::cerr << "foreign_payloads: unexpected type " << type << "\n";
        ++failures;
      }
    } catch (const std::exception& ex) {
      std::cerr << "MISMATCH: " << type << ": " << ex.what() << "\n";
      ++failures;
    }
  }
  std::cout << "foreign_payloads: " << checked - failures << " of " << checked
            << " payloads serialised independently read as written\n";
  return failures == 0 && checked >= 11 ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::cerr << "usage: foreign_payloads write|check FILE\n";
    return 2;
  }
  const std::string mode = argv[1];
  if (mode == "write") return write(argv[2]);
  if (mode == "check") return check(argv[2]);
  std::cerr << "usage: foreign_payloads write|check FILE\n";
  return 2;
}

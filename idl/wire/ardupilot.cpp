#include "swa/wire/ardupilot.h"

namespace swa::wire {

std::optional<std::uint64_t> timestampUsOf(const builtin_interfaces::msg::Time& t) {
  return ardupilot::timestampUsOf(t.sec(), t.nanosec());
}

namespace {

builtin_interfaces::msg::Time timeOf(std::uint64_t timestamp_us) {
  builtin_interfaces::msg::Time t;
  if (const std::optional<ardupilot::RosTime> r = ardupilot::rosTimeOf(timestamp_us)) {
    t.sec(r->sec);
    t.nanosec(r->nanosec);
  }
  return t;
}

}  // namespace

px4::Quaternion attitudeOf(const sensor_msgs::msg::Imu& m, ardupilot::QuaternionLayout layout) {
  const geometry_msgs::msg::Quaternion& q = m.orientation();
  return ardupilot::attitudeOf(q.x(), q.y(), q.z(), q.w(), layout);
}

ardupilot::OrientationFields orientationFieldsOf(const sensor_msgs::msg::Imu& m) {
  const geometry_msgs::msg::Quaternion& q = m.orientation();
  return ardupilot::OrientationFields{q.x(), q.y(), q.z(), q.w()};
}

ardupilot::SpecificForce specificForceOf(const sensor_msgs::msg::Imu& m) {
  const geometry_msgs::msg::Vector3& a = m.linear_acceleration();
  return ardupilot::SpecificForce{a.x(), a.y(), a.z()};
}

sensor_msgs::msg::Imu imuMessage(std::uint64_t timestamp_us, const px4::Quaternion& q,
                                 ardupilot::QuaternionLayout layout,
                                 const std::optional<ardupilot::SpecificForce>& force_frd) {
  sensor_msgs::msg::Imu m;
  m.header().stamp(timeOf(timestamp_us));
  m.header().frame_id(ardupilot::kImuFrame);
  const ardupilot::OrientationFields f = ardupilot::orientationFieldsOf(q, layout);
  m.orientation().x(f.x);
  m.orientation().y(f.y);
  m.orientation().z(f.z);
  m.orientation().w(f.w);
  const ardupilot::SpecificForce a = force_frd ? *force_frd : ardupilot::restingForceOf(q);
  m.linear_acceleration().x(a.x);
  m.linear_acceleration().y(a.y);
  m.linear_acceleration().z(a.z);
  m.angular_velocity_covariance()[0] = -1.0;
  return m;
}

ardupilot_msgs::msg::Status statusMessage(std::uint64_t timestamp_us, bool armed, std::uint8_t mode,
                                          bool failsafe_ekf) {
  ardupilot_msgs::msg::Status m;
  m.header().stamp(timeOf(timestamp_us));
  m.vehicle_type(ardupilot::kVehicleTypeCopter);
  m.armed(armed);
  m.mode(mode);
  m.flying(armed);
  m.external_control(true);  // as ArduPilot sets it (AP_DDS_Client.cpp: "always true for now")
  if (failsafe_ekf) m.failsafe().push_back(ardupilot::kFailsafeEkf);
  return m;
}

ardupilot::NavSatReport navSatReportOf(const sensor_msgs::msg::NavSatFix& m) {
  ardupilot::NavSatReport r;
  r.timestamp_us = timestampUsOf(m.header().stamp()).value_or(0);
  r.status = m.status().status();
  r.latitude_deg = m.latitude();
  r.longitude_deg = m.longitude();
  r.covariance_type = m.position_covariance_type();
  r.variance_east_m2 = m.position_covariance()[0];
  r.variance_north_m2 = m.position_covariance()[4];
  return r;
}

sensor_msgs::msg::NavSatFix navSatFix(std::uint64_t timestamp_us, double lat_deg, double lon_deg, double std_m) {
  sensor_msgs::msg::NavSatFix m;
  m.header().stamp(timeOf(timestamp_us));
  m.header().frame_id("0");  // ArduPilot names the fix by its GPS instance
  m.status().status(0);
  m.status().service(1);  // SERVICE_GPS
  m.latitude(lat_deg);
  m.longitude(lon_deg);
  m.altitude(0.0);
  const double variance = std_m * std_m;
  m.position_covariance()[0] = variance;
  m.position_covariance()[4] = variance;
  m.position_covariance()[8] = 4.0 * variance;
  m.position_covariance_type(2);  // COVARIANCE_TYPE_DIAGONAL_KNOWN
  return m;
}

geometry_msgs::msg::TwistStamped cmdVel(const autopilot::Setpoint& s) {
  const ardupilot::EnuTwist t = ardupilot::enuTwistOf(s.velocity, s.yawspeed_radps);
  geometry_msgs::msg::TwistStamped m;
  m.header().stamp(timeOf(s.timestamp_us));
  m.header().frame_id(ardupilot::kMapFrame);
  m.twist().linear().x(t.east_mps);
  m.twist().linear().y(t.north_mps);
  m.twist().linear().z(t.up_mps);
  m.twist().angular().z(t.yaw_rate_radps);
  return m;
}

CmdVel cmdVelOf(const geometry_msgs::msg::TwistStamped& m) {
  CmdVel c;
  c.map_frame = m.header().frame_id() == ardupilot::kMapFrame;
  c.timestamp_us = timestampUsOf(m.header().stamp());
  c.twist = ardupilot::EnuTwist{m.twist().linear().x(), m.twist().linear().y(), m.twist().linear().z(),
                                m.twist().angular().z()};
  return c;
}

tf2_msgs::msg::TFMessage externalOdometry(const autopilot::Odometry& o, const px4::Quaternion& attitude) {
  geometry_msgs::msg::TransformStamped t;
  t.header().frame_id("odom");
  t.child_frame_id("base_link");
  t.transform().translation().x(o.position_m.y());   // north
  t.transform().translation().y(-o.position_m.x());  // west
  t.transform().translation().z(0.0);
  t.transform().rotation().w(attitude.w);
  t.transform().rotation().x(attitude.x);
  t.transform().rotation().y(-attitude.y);
  t.transform().rotation().z(-attitude.z);
  tf2_msgs::msg::TFMessage m;
  m.transforms().push_back(t);
  return m;
}

std::optional<ExternalOdomReport> externalOdomOf(const tf2_msgs::msg::TFMessage& m) {
  for (const geometry_msgs::msg::TransformStamped& t : m.transforms()) {
    if (t.header().frame_id() != "odom" || t.child_frame_id() != "base_link") continue;
    ExternalOdomReport r;
    r.stamp_ns = static_cast<agent::StampNs>(t.header().stamp().sec()) * 1'000'000'000 +
                 static_cast<agent::StampNs>(t.header().stamp().nanosec());
    r.north_m = t.transform().translation().x();
    r.east_m = -t.transform().translation().y();
    return r;
  }
  return std::nullopt;
}

}  // namespace swa::wire

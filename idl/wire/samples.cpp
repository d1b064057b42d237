#include "swa/wire/samples.h"

namespace swa::wire {

msg::MessageHeader header(agent::StampNs stamp_ns, std::uint32_t seq) {
  msg::MessageHeader h;
  h.stamp_ns(stamp_ns);
  h.seq(seq);
  return h;
}

agent::ImuSample fromMsg(const msg::Imu& m) {
  agent::ImuSample s;
  s.stamp_ns = m.header().stamp_ns();
  s.roll_rad = m.roll_rad();
  s.pitch_rad = m.pitch_rad();
  s.heading_rad = m.heading_rad();
  if (m.has_accelerometer()) {
    agent::AccelerometerSample a;
    a.specific_force_body_mps2 = agent::Vec3(m.accel_x_mps2(), m.accel_y_mps2(), m.accel_z_mps2());
    a.roll_rad = m.accel_roll_rad();
    a.pitch_rad = m.accel_pitch_rad();
    s.accelerometer = a;
  }
  return s;
}

agent::DetectionSet fromMsg(const msg::Detections& m) {
  agent::DetectionSet s;
  s.stamp_ns = m.header().stamp_ns();
  s.detections.reserve(m.items().size());
  for (const msg::Detection& d : m.items()) {
    agent::Detection out;
    out.target_id = d.target_id();
    out.position_body_m = agent::Vec2(d.x_m(), d.y_m());
    if (d.has_covariance()) {
      agent::Mat2 c;
      c << d.cov_xx_m2(), d.cov_xy_m2(), d.cov_xy_m2(), d.cov_yy_m2();
      out.covariance_m2 = c;
    }
    s.detections.push_back(out);
  }
  return s;
}

agent::GnssSample fromMsg(const msg::GnssFix& m) {
  agent::GnssSample s;
  s.stamp_ns = m.header().stamp_ns();
  s.valid = m.valid();
  s.position_m = agent::Vec2(m.x_m(), m.y_m());
  s.std_m = m.std_m();
  return s;
}

agent::VelocityCommand fromMsg(const msg::VelocitySetpoint& m) {
  agent::VelocityCommand c;
  c.stamp_ns = m.header().stamp_ns();
  c.answered_stamp_ns = m.answered_stamp_ns();
  c.seq = m.header().seq();
  c.velocity_mps = agent::Vec2(m.vx_mps(), m.vy_mps());
  c.yaw_rate_radps = m.yaw_rate_radps();
  return c;
}

msg::Imu toMsg(const agent::ImuSample& s, std::uint32_t uav_id, std::uint32_t seq) {
  msg::Imu m;
  m.header(header(s.stamp_ns, seq));
  m.uav_id(uav_id);
  m.roll_rad(s.roll_rad);
  m.pitch_rad(s.pitch_rad);
  m.heading_rad(s.heading_rad);
  m.has_accelerometer(s.accelerometer.has_value());
  if (s.accelerometer) {
    const agent::Vec3& f = s.accelerometer->specific_force_body_mps2;
    m.accel_x_mps2(f.x());
    m.accel_y_mps2(f.y());
    m.accel_z_mps2(f.z());
    m.accel_roll_rad(s.accelerometer->roll_rad);
    m.accel_pitch_rad(s.accelerometer->pitch_rad);
  }
  return m;
}

msg::Detections toMsg(const agent::DetectionSet& s, std::uint32_t observer_id, std::uint32_t seq) {
  msg::Detections m;
  m.header(header(s.stamp_ns, seq));
  m.observer_id(observer_id);
  m.items().reserve(s.detections.size());
  for (const agent::Detection& d : s.detections) {
    msg::Detection out;
    out.target_id(d.target_id);
    out.x_m(d.position_body_m.x());
    out.y_m(d.position_body_m.y());
    out.has_covariance(d.covariance_m2.has_value());
    if (d.covariance_m2) {
      out.cov_xx_m2((*d.covariance_m2)(0, 0));
      out.cov_xy_m2((*d.covariance_m2)(0, 1));
      out.cov_yy_m2((*d.covariance_m2)(1, 1));
    }
    m.items().push_back(out);
  }
  return m;
}

msg::GnssFix toMsg(const agent::GnssSample& s, std::uint32_t uav_id, std::uint32_t seq) {
  msg::GnssFix m;
  m.header(header(s.stamp_ns, seq));
  m.uav_id(uav_id);
  m.valid(s.valid);
  m.x_m(s.position_m.x());
  m.y_m(s.position_m.y());
  m.std_m(s.std_m);
  return m;
}

msg::VelocitySetpoint toMsg(const agent::VelocityCommand& c, std::uint32_t uav_id, std::uint32_t seq,
                            std::uint32_t answered_seq) {
  msg::VelocitySetpoint m;
  m.header(header(c.stamp_ns, seq));
  m.uav_id(uav_id);
  m.vx_mps(c.velocity_mps.x());
  m.vy_mps(c.velocity_mps.y());
  m.answered_stamp_ns(c.answered_stamp_ns);
  m.answered_seq(answered_seq);
  m.yaw_rate_radps(c.yaw_rate_radps);
  return m;
}

}  // namespace swa::wire

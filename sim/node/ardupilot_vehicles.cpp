#include "ardupilot_vehicles.h"

#include <algorithm>

#include <swa/ros/ArdupilotServicesPubSubTypes.h>
#include <swa/ros/ArdupilotStatusPubSubTypes.h>
#include <swa/ros/ImuPubSubTypes.h>
#include <swa/ros/NavSatFixPubSubTypes.h>
#include <swa/ros/TFMessagePubSubTypes.h>
#include <swa/ros/TwistStampedPubSubTypes.h>

#include "swa/dds/qos_profiles.h"
#include "swa/dds/topics.h"
#include "swa/px4/frames.h"
#include "swa/wire/ardupilot.h"
#include "world_command.h"

namespace swa::sim_node {
namespace {

namespace topics = dds::topics;
namespace srv = ardupilot_msgs::srv;
// Where every simulated ArduPilot's fixes are measured from (the world's origin): an airfield, any would do.
const ardupilot::LocalTangent kHome{47.397742, 8.545594};

}  // namespace

ArdupilotVehicles::ArdupilotVehicles(dds::Participant& participant, int uav_count, const sim::VehicleSetup& setup,
                                     agent::ImuSource source) {
  vehicles_.reserve(static_cast<std::size_t>(uav_count));
  for (int i = 0; i < uav_count; ++i) {
    Vehicle& v = vehicles_.emplace_back(setup.guid_timeout_s,
                                        setup.estimator ? std::optional<sim::ArdupilotEstimatorParams>(
                                                              sim::ArdupilotEstimatorParams{setup.ap_external_nav})
                                                        : std::nullopt);
    v.ns = topics::apNamespace(i);
    v.imu.writer = participant.writer<sensor_msgs::msg::ImuPubSubType>(topics::apTopic(v.ns, "imu/experimental/data"),
                                                                       dds::qos::kApOutWriter);
    v.imu.accelerometer_attitude = source == agent::ImuSource::kAccelerometer;
    v.status = participant.writer<ardupilot_msgs::msg::StatusPubSubType>(topics::apTopic(v.ns, "status"),
                                                                         dds::qos::kApStatusWriter);
    if (setup.gnss_source == sim::GnssSource::kAutopilot) {
      v.navsat = participant.writer<sensor_msgs::msg::NavSatFixPubSubType>(topics::apTopic(v.ns, "navsat"),
                                                                           dds::qos::kApOutWriter);
    }
    v.arm_reply = participant.writer<srv::ArmMotors_ResponsePubSubType>(topics::apReply(v.ns, "arm_motors"),
                                                                        dds::qos::kApServiceWriter);
    v.mode_reply = participant.writer<srv::ModeSwitch_ResponsePubSubType>(topics::apReply(v.ns, "mode_switch"),
                                                                          dds::qos::kApServiceWriter);
    v.cmd_vel = participant.readerWithOrigin<geometry_msgs::msg::TwistStampedPubSubType>(
        topics::apTopic(v.ns, "cmd_vel"), dds::qos::kApInReader,
        [this, i](geometry_msgs::msg::TwistStamped&& m, const dds::WriterGuid& w) {
          queue_.push(Arrival{i, Input(std::move(m)), Clock::now(), w});
        });
    v.tf = participant.readerWithOrigin<tf2_msgs::msg::TFMessagePubSubType>(
        topics::apTopic(v.ns, "tf"), dds::qos::kApInReader,
        [this, i](tf2_msgs::msg::TFMessage&& m, const dds::WriterGuid& w) {
          queue_.push(Arrival{i, Input(std::move(m)), Clock::now(), w});
        });
    v.arm_request = participant.readerWithIds<srv::ArmMotors_RequestPubSubType>(
        topics::apRequest(v.ns, "arm_motors"), dds::qos::kApServiceReader,
        [this, i](srv::ArmMotors_Request&& m, const dds::SampleIds& ids) {
          queue_.push(Arrival{i, Input(ArmRequest{std::move(m), ids.self}), Clock::now(), ids.self.writer});
        });
    v.mode_request = participant.readerWithIds<srv::ModeSwitch_RequestPubSubType>(
        topics::apRequest(v.ns, "mode_switch"), dds::qos::kApServiceReader,
        [this, i](srv::ModeSwitch_Request&& m, const dds::SampleIds& ids) {
          queue_.push(Arrival{i, Input(ModeRequest{std::move(m), ids.self}), Clock::now(), ids.self.writer});
        });
    publishStatus(v, 0);  // TRANSIENT_LOCAL: a bridge that starts later learns the state at once
  }
}

void ArdupilotVehicles::unmatched(int uav, std::vector<std::string>& missing) const {
  const Vehicle& v = vehicles_.at(static_cast<std::size_t>(uav));
  if (v.imu.writer.matched() < 1)
    missing.push_back(topics::apTopic(v.ns, "imu/experimental/data") + " (no bridge reading)");
  if (v.cmd_vel.matched() < 1) missing.push_back(topics::apTopic(v.ns, "cmd_vel") + " (no bridge writing)");
  // GNSS from the autopilot (best effort, as ArduPilot sends it): a fix sent before the bridge reads would be lost.
  if (v.navsat && v.navsat.matched() < 1) missing.push_back(topics::apTopic(v.ns, "navsat") + " (no bridge reading)");
}

bool ArdupilotVehicles::publishAttitude(int uav, const agent::ImuSample& s, std::uint32_t seq) {
  Vehicle& v = vehicles_.at(static_cast<std::size_t>(uav));
  // The accelerometer as it flies, once the motors run; disarmed on the ground it reads gravity alone, without the
  // motors' vibration (what --ap-quaternion auto votes on).
  std::optional<ardupilot::SpecificForce> force;
  if (s.accelerometer && v.standin.armed()) {
    const agent::Vec3 f = px4::flippedBody(s.accelerometer->specific_force_body_mps2);
    force = ardupilot::SpecificForce{f.x(), f.y(), f.z()};
  }
  return v.imu.publish(s, seq, [&force](std::uint64_t t_us, const px4::Quaternion& q) {
    return wire::imuMessage(t_us, q, ardupilot::QuaternionLayout::kRos, force);
  });
}

bool ArdupilotVehicles::publishGnss(int uav, const agent::GnssSample& g) {
  Vehicle& v = vehicles_.at(static_cast<std::size_t>(uav));
  const std::optional<std::uint64_t> timestamp = px4::timestampUsOf(g.stamp_ns);
  if (!v.navsat || !timestamp) return false;
  if (!g.valid) return true;  // ArduPilot's silence
  double lat = 0.0, lon = 0.0;
  kHome.latLonOf(g.position_m, lat, lon);
  sensor_msgs::msg::NavSatFix m = wire::navSatFix(*timestamp, lat, lon, g.std_m);
  return v.navsat.write(m);
}

void ArdupilotVehicles::repeatAttitude(int uav) { vehicles_.at(static_cast<std::size_t>(uav)).imu.repeat(); }

void ArdupilotVehicles::drain(std::vector<Answer>& answers, Clock::duration wait, agent::StampNs now,
                              const AdmitFn& admit) {
  arrived_.clear();
  queue_.drain(arrived_, wait);
  for (Arrival& a : arrived_) {
    Vehicle& v = vehicles_[static_cast<std::size_t>(a.uav)];
    if (const auto* cmd = std::get_if<geometry_msgs::msg::TwistStamped>(&a.message)) {
      const wire::CmdVel c = wire::cmdVelOf(*cmd);
      const agent::Vec2 stable = ardupilot::stableVelocityOf(c.twist);
      // Another frame than "map" is not simulated (the stand-in drops it), and answers nothing.
      Answer answer = answerOf(a.uav, a.received, a.writer, stable,
                               worldYawRate(px4::yawspeedOf(c.twist.yaw_rate_radps)), c.map_frame);
      const std::optional<agent::StampNs> answered =
          c.timestamp_us && c.map_frame ? px4::stampNsOf(*c.timestamp_us) : std::nullopt;
      const std::optional<std::uint32_t> seq = answered ? v.imu.published.answer(*answered) : std::nullopt;
      if (!seq) {
        // The bridge's own command (or a repeat): it answers no sample the vehicle is waiting for.
        if (admit(answer)) {
          v.standin.cmdVel(now, c.map_frame, c.twist);
          if (c.map_frame) v.yaw_rate_radps = answer.setpoint.yaw_rate_radps();
        }
        continue;
      }
      markAnswered(answer, *answered, *seq);
      answers.push_back(std::move(answer));
    } else if (const auto* arm = std::get_if<ArmRequest>(&a.message)) {
      srv::ArmMotors_Response reply;
      reply.result(v.standin.armMotors(arm->request.arm()));
      v.arm_reply.writeReply(reply, arm->id);
    } else if (const auto* mode = std::get_if<ModeRequest>(&a.message)) {
      const sim::ArdupilotStandin::ModeReply r = v.standin.modeSwitch(mode->request.mode());
      srv::ModeSwitch_Response reply;
      reply.status(r.status);
      reply.curr_mode(r.curr_mode);
      v.mode_reply.writeReply(reply, mode->id);
    } else if (const auto* tf = std::get_if<tf2_msgs::msg::TFMessage>(&a.message)) {
      if (const std::optional<wire::ExternalOdomReport> r = wire::externalOdomOf(*tf)) {
        v.standin.externalOdometry(now, r->stamp_ns);
      }
    }
  }
}

void ArdupilotVehicles::apply(const Answer& a) {
  Vehicle& v = vehicles_.at(static_cast<std::size_t>(a.uav));
  const ardupilot::EnuTwist twist{a.setpoint.vx_mps(), a.setpoint.vy_mps(), 0.0, a.setpoint.yaw_rate_radps()};
  v.standin.cmdVel(a.setpoint.answered_stamp_ns(), true, twist);
  v.yaw_rate_radps = a.setpoint.yaw_rate_radps();
}

void ArdupilotVehicles::step(sim::World& world, const EventFn& event) {
  for (std::size_t k = 0; k < vehicles_.size(); ++k) {
    Vehicle& v = vehicles_[k];
    stepVehicle(world, static_cast<int>(k), v.standin, v.yaw_rate_radps, "ArduPilot stand-in " + v.ns, event);
    publishStatus(v, world.time_ns());
  }
}

std::string ArdupilotVehicles::commandTopic(int uav) const {
  return topics::apTopic(vehicles_.at(static_cast<std::size_t>(uav)).ns, "cmd_vel");
}

void ArdupilotVehicles::publishStatus(Vehicle& v, agent::StampNs now) {
  const sim::ArdupilotStandin& s = v.standin;
  if (v.status_sent && s.armed() == v.status_armed && s.mode() == v.status_mode &&
      s.ekfFailsafe() == v.status_ekf_failsafe) {
    return;
  }
  const std::uint64_t timestamp = px4::timestampUsOf(now).value_or(0);
  ardupilot_msgs::msg::Status m = wire::statusMessage(timestamp, s.armed(), s.mode(), s.ekfFailsafe());
  v.status.write(m);
  v.status_sent = true;
  v.status_armed = s.armed();
  v.status_mode = s.mode();
  v.status_ekf_failsafe = s.ekfFailsafe();
}

}  // namespace swa::sim_node

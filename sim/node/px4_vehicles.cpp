#include "px4_vehicles.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <swa/px4/OffboardControlMode_v1_15PubSubTypes.h>
#include <swa/px4/SensorCombined_v1_15PubSubTypes.h>
#include <swa/px4/SensorGps_v1_15PubSubTypes.h>
#include <swa/px4/SensorGps_v1_17PubSubTypes.h>
#include <swa/px4/TrajectorySetpoint_v1_15PubSubTypes.h>
#include <swa/px4/VehicleAttitude_v1_15PubSubTypes.h>
#include <swa/px4/VehicleCommandAck_v1_15PubSubTypes.h>
#include <swa/px4/VehicleCommand_v1_15PubSubTypes.h>
#include <swa/px4/VehicleLocalPosition_v1_15PubSubTypes.h>
#include <swa/px4/VehicleLocalPosition_v1_16PubSubTypes.h>
#include <swa/px4/VehicleOdometry_v1_15PubSubTypes.h>
#include <swa/px4/VehicleStatus_v1_15PubSubTypes.h>
#include <swa/px4/VehicleStatus_v1_16PubSubTypes.h>

#include "swa/dds/qos_profiles.h"
#include "swa/dds/topics.h"
#include "swa/px4/frames.h"
#include "swa/px4/release.h"
#include "swa/wire/px4.h"
#include "world_command.h"

namespace swa::sim_node {
namespace {

namespace topics = dds::topics;
constexpr agent::StampNs kStatusPeriodNs = 200'000'000;  // vehicle_status at 5 Hz, as PX4 sends it
// Where every stand-in's EKF2 sets its first global origin: the world's origin on the ground, at PX4 SITL's default
// home (PX4_HOME_LAT, PX4_HOME_LON), where the ArduPilot stand-in's home is too.
const px4::GeoPoint kAirfield{47.397742, 8.545594};
// The world's east, north are PX4's local frame around the airfield: PX4's own projection places them on the ground.
const px4::MapProjection kAirfieldFrame(kAirfield);

std::optional<agent::StampNs> shiftTime(double at_s) {
  if (!std::isfinite(at_s)) return std::nullopt;
  return static_cast<agent::StampNs>(std::llround(at_s * 1e9));
}

}  // namespace

Px4Vehicles::Px4Vehicles(dds::Participant& participant, int uav_count, const sim::VehicleSetup& setup,
                         agent::ImuSource source)
    : shift_{shiftTime(setup.px4_origin_shift_at_s),
             px4::NedPoint{setup.px4_origin_shift_north_m, setup.px4_origin_shift_east_m}} {
  vehicles_.reserve(static_cast<std::size_t>(uav_count));
  const std::string status_topic = px4::topicName(setup.px4_release, "vehicle_status");
  const std::string gps_topic = px4::topicName(setup.px4_release, "vehicle_gps_position");
  const std::string position_topic = px4::topicName(setup.px4_release, "vehicle_local_position");
  const bool gnss = setup.gnss_source == sim::GnssSource::kAutopilot;
  for (int i = 0; i < uav_count; ++i) {
    Vehicle& v = vehicles_.emplace_back(
        setup.com_of_loss_t_s, setup.estimator ? std::optional<sim::Px4EstimatorParams>(sim::Px4EstimatorParams{
                                                     setup.ekf2_noaid_tout_s, setup.ekf2_ev_ctrl})
                                               : std::nullopt);
    v.ns = topics::px4Namespace(i);
    v.attitude.writer = participant.writer<px4_msgs::msg::VehicleAttitudePubSubType>(
        topics::px4Out(v.ns, "vehicle_attitude"), dds::qos::kPx4OutWriter);
    v.attitude.accelerometer_attitude = source == agent::ImuSource::kAccelerometer;
    v.accelerometer = participant.writer<px4_msgs::msg::SensorCombinedPubSubType>(
        topics::px4Out(v.ns, "sensor_combined"), dds::qos::kPx4OutWriter);
    if (px4::hasV116VehicleStatus(setup.px4_release)) {
      v.status_v1_16 = participant.writer<px4_v1_16::px4_msgs::msg::VehicleStatusPubSubType>(
          topics::px4Out(v.ns, status_topic), dds::qos::kPx4OutWriter);
    } else {
      v.status = participant.writer<px4_msgs::msg::VehicleStatusPubSubType>(topics::px4Out(v.ns, status_topic),
                                                                            dds::qos::kPx4OutWriter);
    }
    if (gnss && px4::hasV117SensorGps(setup.px4_release)) {
      v.gps_v1_17 = participant.writer<px4_v1_17::px4_msgs::msg::SensorGpsPubSubType>(topics::px4Out(v.ns, gps_topic),
                                                                                      dds::qos::kPx4OutWriter);
    } else if (gnss) {
      v.gps = participant.writer<px4_msgs::msg::SensorGpsPubSubType>(topics::px4Out(v.ns, gps_topic),
                                                                     dds::qos::kPx4OutWriter);
    }
    if (gnss && px4::hasV116VehicleLocalPosition(setup.px4_release)) {
      v.position_v1_16 = participant.writer<px4_v1_16::px4_msgs::msg::VehicleLocalPositionPubSubType>(
          topics::px4Out(v.ns, position_topic), dds::qos::kPx4OutWriter);
    } else if (gnss) {
      v.position = participant.writer<px4_msgs::msg::VehicleLocalPositionPubSubType>(
          topics::px4Out(v.ns, position_topic), dds::qos::kPx4OutWriter);
    }
    v.ack = participant.writer<px4_msgs::msg::VehicleCommandAckPubSubType>(topics::px4Out(v.ns, "vehicle_command_ack"),
                                                                           dds::qos::kPx4OutWriter);
    const auto arrive = [this, i](auto&& m, const dds::WriterGuid& w) {
      queue_.push(Arrival{i, Input(std::move(m)), Clock::now(), w});
    };
    v.setpoint = participant.readerWithOrigin<px4_msgs::msg::TrajectorySetpointPubSubType>(
        topics::px4In(v.ns, "trajectory_setpoint"), dds::qos::kPx4InReader, arrive);
    v.mode = participant.readerWithOrigin<px4_msgs::msg::OffboardControlModePubSubType>(
        topics::px4In(v.ns, "offboard_control_mode"), dds::qos::kPx4InReader, arrive);
    v.command = participant.readerWithOrigin<px4_msgs::msg::VehicleCommandPubSubType>(
        topics::px4In(v.ns, "vehicle_command"), dds::qos::kPx4InReader, arrive);
    v.odometry = participant.readerWithOrigin<px4_msgs::msg::VehicleOdometryPubSubType>(
        topics::px4In(v.ns, "vehicle_visual_odometry"), dds::qos::kPx4InReader, arrive);
    publishStatus(i, v, 0);  // TRANSIENT_LOCAL: a bridge that starts later learns the state at once
  }
}

void Px4Vehicles::unmatched(int uav, std::vector<std::string>& missing) const {
  const Vehicle& v = vehicles_.at(static_cast<std::size_t>(uav));
  if (v.attitude.writer.matched() < 1)
    missing.push_back(topics::px4Out(v.ns, "vehicle_attitude") + " (no bridge reading)");
  if (v.setpoint.matched() < 1) missing.push_back(topics::px4In(v.ns, "trajectory_setpoint") + " (no bridge writing)");
  if (v.mode.matched() < 1) missing.push_back(topics::px4In(v.ns, "offboard_control_mode") + " (no bridge writing)");
  // GNSS from the autopilot (best effort, as PX4 sends it): a fix sent before the bridge reads would be lost.
  const int gps = v.gps ? v.gps.matched() : v.gps_v1_17 ? v.gps_v1_17.matched() : 1;
  const int position = v.position ? v.position.matched() : v.position_v1_16 ? v.position_v1_16.matched() : 1;
  if (gps < 1 || position < 1) {
    missing.push_back(v.ns + "'s vehicle_gps_position / vehicle_local_position (no bridge reading)");
  }
}

bool Px4Vehicles::publishAttitude(int uav, const agent::ImuSample& s, std::uint32_t seq) {
  Vehicle& v = vehicles_.at(static_cast<std::size_t>(uav));
  bool ok = true;
  // The accelerometer first, so that the bridge has it when the attitude of the same instant arrives.
  const std::optional<std::uint64_t> timestamp = px4::timestampUsOf(s.stamp_ns);
  if (s.accelerometer && timestamp) {
    px4_msgs::msg::SensorCombined m =
        wire::sensorCombined(*timestamp, px4::flippedBody(s.accelerometer->specific_force_body_mps2));
    ok = v.accelerometer.write(m);
  }
  return v.attitude.publish(s, seq, wire::vehicleAttitude) && ok;
}

bool Px4Vehicles::publishGnss(int uav, const agent::GnssSample& g) {
  Vehicle& v = vehicles_.at(static_cast<std::size_t>(uav));
  const std::optional<std::uint64_t> timestamp = px4::timestampUsOf(g.stamp_ns);
  if (!timestamp) return false;
  bool ok = false;
  // The fix first: the bridge judges each position by the newest fix it has.
  if (v.gps_v1_17) {
    auto m = wire::sensorGps<px4_v1_17::px4_msgs::msg::SensorGps>(*timestamp, g);
    ok = v.gps_v1_17.write(m);
  } else if (v.gps) {
    auto m = wire::sensorGps<px4_msgs::msg::SensorGps>(*timestamp, g);
    ok = v.gps.write(m);
  }
  // The local position's validity is EKF2's (px4_estimator.h), with this fix fused: with external vision fused it
  // outlives the fix.
  v.standin.gnss(g.stamp_ns, g.valid);
  const std::optional<bool> valid =
      v.standin.modelsEstimator() ? std::optional<bool>(v.standin.localPositionValid()) : std::nullopt;
  const bool dead_reckoning = v.standin.deadReckoning();
  if (!v.position_v1_16 && !v.position) return ok;
  const wire::LocalReference& reference = referenceAt(uav, v, g.stamp_ns, *timestamp);
  const agent::GnssSample local = inLocalFrame(v, g);
  if (v.position_v1_16) {
    auto m = wire::vehicleLocalPosition<px4_v1_16::px4_msgs::msg::VehicleLocalPosition>(*timestamp, local, valid,
                                                                                        dead_reckoning, reference);
    ok = v.position_v1_16.write(m) && ok;
  } else {
    auto m = wire::vehicleLocalPosition<px4_msgs::msg::VehicleLocalPosition>(*timestamp, local, valid, dead_reckoning,
                                                                             reference);
    ok = v.position.write(m) && ok;
  }
  return ok;
}

const wire::LocalReference& Px4Vehicles::referenceAt(int uav, Vehicle& v, agent::StampNs now,
                                                     std::uint64_t timestamp_us) {
  if (!v.reference) v.reference = wire::LocalReference{timestamp_us, kAirfield};
  if (v.moved || !shift_.at || now < *shift_.at) return *v.reference;
  // EKF2's setEkfGlobalOrigin: the new origin, stamped now; every position from here on is re-based on it.
  const px4::GeoPoint to = px4::MapProjection(v.reference->point).reproject(shift_.by);
  v.reference = wire::LocalReference{timestamp_us, to};
  v.moved.emplace(to);
  std::fprintf(stderr,
               "swa_sim: t = %.2f s: UAV %d: PX4 stand-in %s moved its local origin %.2f m east, %.2f m north "
               "(ref_timestamp %llu): x, y re-based on it\n",
               static_cast<double>(now) * 1e-9, uav, v.ns.c_str(), shift_.by.east_m, shift_.by.north_m,
               static_cast<unsigned long long>(timestamp_us));
  return *v.reference;
}

agent::GnssSample Px4Vehicles::inLocalFrame(const Vehicle& v, agent::GnssSample g) const {
  if (!v.moved) return g;  // around the airfield: the world's own coordinates, bit for bit as before issue #46
  // The same point on the ground, projected around the moved origin, as EKF2 re-bases its position.
  const px4::NedPoint p = v.moved->project(kAirfieldFrame.reproject({g.position_m.y(), g.position_m.x()}));
  g.position_m = agent::Vec2(p.east_m, p.north_m);
  return g;
}

void Px4Vehicles::repeatAttitude(int uav) { vehicles_.at(static_cast<std::size_t>(uav)).attitude.repeat(); }

void Px4Vehicles::drain(std::vector<Answer>& answers, Clock::duration wait, agent::StampNs now, const AdmitFn& admit) {
  arrived_.clear();
  queue_.drain(arrived_, wait);
  for (Arrival& a : arrived_) {
    Vehicle& v = vehicles_[static_cast<std::size_t>(a.uav)];
    if (const auto* sp = std::get_if<px4_msgs::msg::TrajectorySetpoint>(&a.message)) {
      const px4::NedVelocity ned = wire::velocityOf(*sp);
      const agent::Vec2 stable = px4::stableOf(ned);
      Answer answer =
          answerOf(a.uav, a.received, a.writer, stable, worldYawRate(wire::yawspeedOf(*sp)), wire::isVelocityOnly(*sp));
      const std::optional<agent::StampNs> answered = px4::stampNsOf(sp->timestamp());
      const std::optional<std::uint32_t> seq = answered ? v.attitude.published.answer(*answered) : std::nullopt;
      if (!seq) {
        // The bridge's own setpoint (or a repeat): it answers no sample the vehicle is waiting for.
        if (admit(answer)) {
          v.standin.trajectorySetpoint(ned, answer.velocity_only);
          v.yaw_rate_radps = answer.setpoint.yaw_rate_radps();
        }
        continue;
      }
      markAnswered(answer, *answered, *seq);
      answers.push_back(std::move(answer));
    } else if (const auto* mode = std::get_if<px4_msgs::msg::OffboardControlMode>(&a.message)) {
      v.standin.offboardControlMode(now, wire::isVelocityControl(*mode));
    } else if (const auto* cmd = std::get_if<px4_msgs::msg::VehicleCommand>(&a.message)) {
      px4_msgs::msg::VehicleCommandAck ack;
      ack.timestamp(px4::timestampUsOf(now).value_or(0));
      ack.command(cmd->command());
      ack.result(v.standin.vehicleCommand(now, cmd->command(), cmd->param1(), cmd->param2()));
      ack.target_system(cmd->source_system());
      ack.target_component(cmd->source_component());
      ack.from_external(false);
      v.ack.write(ack);
      ++acks_;
    } else if (const auto* odometry = std::get_if<px4_msgs::msg::VehicleOdometry>(&a.message)) {
      const wire::VisionReport r = wire::visionReportOf(*odometry);
      v.standin.visualOdometry(now, r.position, r.velocity);
    }
  }
}

void Px4Vehicles::apply(const Answer& a) {
  Vehicle& v = vehicles_.at(static_cast<std::size_t>(a.uav));
  v.standin.trajectorySetpoint(px4::nedOf(agent::Vec2(a.setpoint.vx_mps(), a.setpoint.vy_mps())), a.velocity_only);
  v.yaw_rate_radps = a.setpoint.yaw_rate_radps();
}

void Px4Vehicles::step(sim::World& world, const EventFn& event) {
  for (std::size_t k = 0; k < vehicles_.size(); ++k) {
    Vehicle& v = vehicles_[k];
    stepVehicle(world, static_cast<int>(k), v.standin, v.yaw_rate_radps, "PX4 stand-in " + v.ns, event);
    publishStatus(static_cast<int>(k), v, world.time_ns());
  }
}

std::string Px4Vehicles::commandTopic(int uav) const {
  return topics::px4In(vehicles_.at(static_cast<std::size_t>(uav)).ns, "trajectory_setpoint");
}

void Px4Vehicles::publishStatus(int uav, Vehicle& v, agent::StampNs now) {
  const sim::Px4Standin& s = v.standin;
  const bool changed = s.navState() != v.status_sent_nav || s.armingState() != v.status_sent_arming;
  if (!changed && now - v.status_sent_at < kStatusPeriodNs) return;
  const std::uint64_t timestamp = px4::timestampUsOf(now).value_or(0);
  const auto system_id = static_cast<std::uint8_t>(uav + 1);
  if (v.status_v1_16) {
    auto m = wire::vehicleStatus<px4_v1_16::px4_msgs::msg::VehicleStatus>(timestamp, s.armingState(), s.navState(),
                                                                          s.failsafe(), system_id);
    v.status_v1_16.write(m);
  } else {
    auto m = wire::vehicleStatus<px4_msgs::msg::VehicleStatus>(timestamp, s.armingState(), s.navState(), s.failsafe(),
                                                               system_id);
    v.status.write(m);
  }
  v.status_sent_nav = s.navState();
  v.status_sent_arming = s.armingState();
  v.status_sent_at = now;
}

}  // namespace swa::sim_node

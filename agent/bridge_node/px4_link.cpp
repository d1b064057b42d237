// PX4's side of the bridge: its uXRCE-DDS topics of one release under the namespace NS (vehicle_link.h).

#include <array>
#include <cstdio>
#include <mutex>
#include <optional>
#include <string>
#include <utility>

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
#include "swa/px4/accelerometer.h"
#include "swa/px4/gnss.h"
#include "swa/px4/release.h"
#include "swa/px4/vehicle.h"
#include "swa/wire/px4.h"
#include "vehicle_link.h"

namespace swa::bridge_node {
namespace {

namespace topics = dds::topics;

class Px4Link : public VehicleLink {
 public:
  Px4Link(const BridgeOptions& options, VehicleEvents events)
      : options_(options),
        ns_(px4Namespace(options)),
        status_topic_(px4::topicName(options.px4_release, "vehicle_status")),
        events_(std::move(events)) {}

  void connect(dds::Participant& p) override {
    setpoint_ = p.writer<px4_msgs::msg::TrajectorySetpointPubSubType>(topics::px4In(ns_, "trajectory_setpoint"),
                                                                      dds::qos::kPx4InWriter);
    offboard_ = p.writer<px4_msgs::msg::OffboardControlModePubSubType>(topics::px4In(ns_, "offboard_control_mode"),
                                                                       dds::qos::kPx4InWriter);
    if (options_.core.engage) {
      vehicle_command_ = p.writer<px4_msgs::msg::VehicleCommandPubSubType>(topics::px4In(ns_, "vehicle_command"),
                                                                           dds::qos::kPx4InWriter);
    }
    if (options_.odometry.mode != autopilot::OdometryMode::kOff) {
      odometry_ = p.writer<px4_msgs::msg::VehicleOdometryPubSubType>(odometryTopic(), dds::qos::kPx4InWriter);
    }
    const auto status = [this](bool armed, std::uint8_t nav_state) { events_.status(armed, nav_state); };
    if (px4::hasV116VehicleStatus(options_.px4_release)) {
      status_reader_v1_16_ = p.reader<px4_v1_16::px4_msgs::msg::VehicleStatusPubSubType>(
          topics::px4Out(ns_, status_topic_), dds::qos::kPx4OutReader,
          [status](px4_v1_16::px4_msgs::msg::VehicleStatus&& m) {
            status(m.arming_state() == px4::kArmingStateArmed, m.nav_state());
          });
    } else {
      status_reader_ = p.reader<px4_msgs::msg::VehicleStatusPubSubType>(
          topics::px4Out(ns_, status_topic_), dds::qos::kPx4OutReader, [status](px4_msgs::msg::VehicleStatus&& m) {
            status(m.arming_state() == px4::kArmingStateArmed, m.nav_state());
          });
    }
    ack_reader_ = p.reader<px4_msgs::msg::VehicleCommandAckPubSubType>(
        topics::px4Out(ns_, "vehicle_command_ack"), dds::qos::kPx4OutReader,
        [this](px4_msgs::msg::VehicleCommandAck&& m) { onAck(m); });
    if (!options_.no_gnss) connectGnss(p);
    // The accelerometer first: each attitude takes the reading of its instant, if there is one (accelerometer.h).
    accel_reader_ = p.reader<px4_msgs::msg::SensorCombinedPubSubType>(
        topics::px4Out(ns_, "sensor_combined"), dds::qos::kPx4OutReader, [this](px4_msgs::msg::SensorCombined&& m) {
          const std::array<float, 3>& a = m.accelerometer_m_s2();
          const float accel[3] = {a[0], a[1], a[2]};
          const std::lock_guard<std::mutex> lock(accel_mutex_);
          accel_.onSensorCombined(m.timestamp(), m.accelerometer_timestamp_relative(), accel);
        });
    attitude_reader_ = p.reader<px4_msgs::msg::VehicleAttitudePubSubType>(
        topics::px4Out(ns_, "vehicle_attitude"), dds::qos::kPx4OutReader, [this](px4_msgs::msg::VehicleAttitude&& m) {
          std::optional<ardupilot::SpecificForce> force;
          {
            const std::lock_guard<std::mutex> lock(accel_mutex_);
            if (const auto r = accel_.pairWith(m.timestamp_sample()))
              force = ardupilot::SpecificForce{r->x, r->y, r->z};
          }
          events_.attitude(m.timestamp(), wire::quaternionOf(m), force);
        });
  }

  bool readsCommands() const override { return setpoint_.matched() > 0 && offboard_.matched() > 0; }
  bool attitudeMatched() const override { return attitude_reader_.matched() > 0; }
  // The acknowledgement is only logged, and not every PX4 build sends it: the command writer alone.
  bool requestsMatched() const override { return vehicle_command_.matched() > 0; }

  void send(const autopilot::Outbox& out) override {
    if (out.setpoint) {
      px4_msgs::msg::TrajectorySetpoint m = wire::trajectorySetpoint(*out.setpoint);
      setpoint_.write(m);
    }
    if (out.heartbeat_us) {
      px4_msgs::msg::OffboardControlMode m = wire::velocityControlMode(*out.heartbeat_us);
      offboard_.write(m);
    }
    if (out.request && vehicle_command_) {
      px4_msgs::msg::VehicleCommand m =
          wire::vehicleCommand(*out.request, static_cast<std::uint8_t>(options_.target_system));
      vehicle_command_.write(m);
    }
  }

  std::string description() const override {
    return std::string("PX4 ") + px4::releaseName(options_.px4_release) + " namespace '" + ns_ + "' (" +
           topics::px4Out(ns_, "vehicle_attitude") + ", " + status_topic_ + ")";
  }
  std::string commandTopic() const override { return topics::px4In(ns_, "trajectory_setpoint"); }
  std::string noReaderHint() const override {
    return "is PX4's uXRCE-DDS agent on this domain, with namespace '" + ns_ + "'?";
  }
  void sendOdometry(const autopilot::Odometry& o, const px4::Quaternion&) override {
    if (!odometry_) return;
    px4_msgs::msg::VehicleOdometry m = wire::vehicleOdometry(o);
    odometry_.write(m);
  }
  std::string odometryTopic() const override { return topics::px4In(ns_, "vehicle_visual_odometry"); }
  std::string odometryHint() const override {
    return "set EKF2_EV_CTRL = 5 (horizontal position and velocity; PX4's default is 0 from v1.16) and keep "
           "EKF2_HGT_REF on the barometer (deploy/README.md, \"External odometry\")";
  }

  std::optional<px4::GnssForwardCounters> gnssCounters() const override {
    if (options_.no_gnss) return std::nullopt;
    const std::lock_guard<std::mutex> lock(gnss_mutex_);
    return gnss_forward_.counters();
  }

  std::string noStatusHint() const override {
    return "no " + topics::px4Out(ns_, status_topic_) + ": is the vehicle PX4 " +
           px4::releaseName(options_.px4_release) +
           "? (--px4-release; v1.15 names it vehicle_status, v1.16 and later vehicle_status_v1 with another layout)";
  }

 private:
  void connectGnss(dds::Participant& p) {
    const px4::Release r = options_.px4_release;
    const std::string gps_topic = topics::px4Out(ns_, px4::topicName(r, "vehicle_gps_position"));
    const std::string position_topic = topics::px4Out(ns_, px4::topicName(r, "vehicle_local_position"));
    if (px4::hasV117SensorGps(r)) {
      gps_reader_v1_17_ = p.reader<px4_v1_17::px4_msgs::msg::SensorGpsPubSubType>(
          gps_topic, dds::qos::kPx4OutReader,
          [this](px4_v1_17::px4_msgs::msg::SensorGps&& m) { onGps(wire::gpsReportOf(m)); });
    } else {
      gps_reader_ = p.reader<px4_msgs::msg::SensorGpsPubSubType>(
          gps_topic, dds::qos::kPx4OutReader, [this](px4_msgs::msg::SensorGps&& m) { onGps(wire::gpsReportOf(m)); });
    }
    if (px4::hasV116VehicleLocalPosition(r)) {
      position_reader_v1_16_ = p.reader<px4_v1_16::px4_msgs::msg::VehicleLocalPositionPubSubType>(
          position_topic, dds::qos::kPx4OutReader,
          [this](px4_v1_16::px4_msgs::msg::VehicleLocalPosition&& m) { onLocalPosition(wire::localPositionOf(m)); });
    } else {
      position_reader_ = p.reader<px4_msgs::msg::VehicleLocalPositionPubSubType>(
          position_topic, dds::qos::kPx4OutReader,
          [this](px4_msgs::msg::VehicleLocalPosition&& m) { onLocalPosition(wire::localPositionOf(m)); });
    }
  }

  // The fix and the position arrive on two readers (two threads): GnssForward pairs them under its own lock.
  void onGps(const px4::GpsReport& gps) {
    const std::lock_guard<std::mutex> lock(gnss_mutex_);
    gnss_forward_.onGps(gps);
  }
  void onLocalPosition(const px4::LocalPositionReport& position) {
    const std::lock_guard<std::mutex> lock(gnss_mutex_);
    const std::optional<agent::GnssSample> g = gnss_forward_.onLocalPosition(position);
    // A moved origin is logged before the first sample placed by it goes out.
    for (const std::string& line : gnss_forward_.takeEvents()) events_.log(line);
    if (g) events_.gnss(*g);
    events_.estimator(position.dead_reckoning);
  }

  void onAck(const px4_msgs::msg::VehicleCommandAck& m) {
    const char* what = m.command() == px4::kCmdComponentArmDisarm ? "arm"
                       : m.command() == px4::kCmdDoSetMode        ? "offboard"
                                                                  : "?";
    events_.log(std::string("PX4 answered the ") + what + " request: result " + std::to_string(m.result()) +
                " (0 accepted)");
  }

  const BridgeOptions options_;
  const std::string ns_;
  const std::string status_topic_;  // the release's name of vehicle_status
  const VehicleEvents events_;

  mutable std::mutex gnss_mutex_;
  px4::GnssForward gnss_forward_;
  std::mutex accel_mutex_;
  px4::AccelerometerPairing accel_;

  dds::Writer<px4_msgs::msg::TrajectorySetpoint> setpoint_;
  dds::Writer<px4_msgs::msg::OffboardControlMode> offboard_;
  dds::Writer<px4_msgs::msg::VehicleCommand> vehicle_command_;  // --engage only
  dds::Writer<px4_msgs::msg::VehicleOdometry> odometry_;        // not with --odometry off
  dds::Reader<px4_msgs::msg::VehicleAttitude> attitude_reader_;
  dds::Reader<px4_msgs::msg::SensorCombined> accel_reader_;                   // sensor_combined: the accelerometer
  dds::Reader<px4_msgs::msg::VehicleStatus> status_reader_;                   // v1.15
  dds::Reader<px4_v1_16::px4_msgs::msg::VehicleStatus> status_reader_v1_16_;  // v1.16 and later
  dds::Reader<px4_msgs::msg::VehicleCommandAck> ack_reader_;
  // The release's layouts of PX4's fix and local position (one of each pair), not with --no-gnss.
  dds::Reader<px4_msgs::msg::SensorGps> gps_reader_;
  dds::Reader<px4_v1_17::px4_msgs::msg::SensorGps> gps_reader_v1_17_;
  dds::Reader<px4_msgs::msg::VehicleLocalPosition> position_reader_;
  dds::Reader<px4_v1_16::px4_msgs::msg::VehicleLocalPosition> position_reader_v1_16_;
};

}  // namespace

std::unique_ptr<VehicleLink> makePx4Link(const BridgeOptions& options, VehicleEvents events) {
  return std::make_unique<Px4Link>(options, std::move(events));
}

}  // namespace swa::bridge_node

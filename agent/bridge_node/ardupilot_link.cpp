// ArduPilot's side of the bridge (AP_DDS, Copter 4.5+) under the namespace NS (vehicle_link.h, swa/autopilot/
// ardupilot.h): its IMU message's orientation in (in the field order --ap-quaternion gives or gravity tells,
// swa/autopilot/quaternion_order.h), its status in, its GNSS fix in (navsat, swa/autopilot/navsat.h;
// not with --no-gnss), the core's setpoints out as cmd_vel in frame "map" (ENU), and with --engage its arm_motors and
// mode_switch services.
// ArduPilot has no offboard heartbeat: its liveness is the command stream itself, and when that stops its GUIDED
// velocity timeout (GUID_TIMEOUT) stops the vehicle (the core, told so, puts no heartbeat in the outbox).

#include <algorithm>
#include <array>
#include <atomic>
#include <cstdio>
#include <mutex>
#include <optional>
#include <utility>

#include <swa/ros/ArdupilotServicesPubSubTypes.h>
#include <swa/ros/ArdupilotStatusPubSubTypes.h>
#include <swa/ros/ImuPubSubTypes.h>
#include <swa/ros/NavSatFixPubSubTypes.h>
#include <swa/ros/TFMessagePubSubTypes.h>
#include <swa/ros/TwistStampedPubSubTypes.h>

#include "swa/autopilot/ardupilot.h"
#include "swa/autopilot/navsat.h"
#include "swa/autopilot/quaternion_order.h"
#include "swa/dds/qos_profiles.h"
#include "swa/dds/topics.h"
#include "swa/wire/ardupilot.h"
#include "vehicle_link.h"

namespace swa::bridge_node {
namespace {

namespace topics = dds::topics;
namespace srv = ardupilot_msgs::srv;

class ArdupilotLink : public VehicleLink {
 public:
  ArdupilotLink(const BridgeOptions& options, VehicleEvents events)
      : options_(options), ns_(apNamespace(options)), events_(std::move(events)), navsat_(options.navsat) {}

  void connect(dds::Participant& p) override {
    cmd_vel_ =
        p.writer<geometry_msgs::msg::TwistStampedPubSubType>(topics::apTopic(ns_, "cmd_vel"), dds::qos::kApInWriter);
    if (options_.odometry.mode != autopilot::OdometryMode::kOff) {
      tf_ = p.writer<tf2_msgs::msg::TFMessagePubSubType>(odometryTopic(), dds::qos::kApInWriter);
    }
    if (options_.core.engage) {
      arm_request_ =
          p.writer<srv::ArmMotors_RequestPubSubType>(topics::apRequest(ns_, "arm_motors"), dds::qos::kApServiceWriter);
      mode_request_ = p.writer<srv::ModeSwitch_RequestPubSubType>(topics::apRequest(ns_, "mode_switch"),
                                                                  dds::qos::kApServiceWriter);
      arm_reply_ = p.readerWithIds<srv::ArmMotors_ResponsePubSubType>(
          topics::apReply(ns_, "arm_motors"), dds::qos::kApServiceReader,
          [this](srv::ArmMotors_Response&& m, const dds::SampleIds& ids) {
            if (isOurs(ids))
              events_.log(std::string("ArduPilot answered the arm request: ") + (m.result() ? "armed" : "refused"));
          });
      mode_reply_ = p.readerWithIds<srv::ModeSwitch_ResponsePubSubType>(
          topics::apReply(ns_, "mode_switch"), dds::qos::kApServiceReader,
          [this](srv::ModeSwitch_Response&& m, const dds::SampleIds& ids) {
            if (isOurs(ids)) {
              events_.log(std::string("ArduPilot answered the GUIDED request: ") +
                          (m.status() ? "switched" : "refused") + ", mode now " +
                          ardupilot::copterModeName(m.curr_mode()) + " (" + std::to_string(m.curr_mode()) + ")");
            }
          });
    }
    if (!options_.no_gnss) {
      navsat_reader_ = p.reader<sensor_msgs::msg::NavSatFixPubSubType>(
          topics::apTopic(ns_, "navsat"), dds::qos::kApOutReader, [this](sensor_msgs::msg::NavSatFix&& m) {
            const std::lock_guard<std::mutex> lock(gnss_mutex_);
            if (const auto g = navsat_.onNavSat(wire::navSatReportOf(m))) events_.gnss(*g);
          });
    }
    status_reader_ = p.reader<ardupilot_msgs::msg::StatusPubSubType>(
        topics::apTopic(ns_, "status"), dds::qos::kApStatusReader, [this](ardupilot_msgs::msg::Status&& m) {
          disarmed_ = !m.armed();
          events_.status(m.armed(), m.mode());
          const auto& failsafes = m.failsafe();
          events_.estimator(std::find(failsafes.begin(), failsafes.end(), ardupilot::kFailsafeEkf) != failsafes.end());
        });
    imu_reader_ = p.reader<sensor_msgs::msg::ImuPubSubType>(
        topics::apTopic(ns_, "imu/experimental/data"), dds::qos::kApOutReader, [this](sensor_msgs::msg::Imu&& m) {
          const std::optional<std::uint64_t> t = wire::timestampUsOf(m.header().stamp());
          if (!t) {  // a negative time or nanosec >= 1e9: no instant to stamp the sample with
            if (bad_stamps_++ == 0) {
              events_.log("dropping IMU messages with an invalid stamp (negative, or nanosec >= 1e9)");
            }
            return;
          }
          if (const std::optional<ardupilot::QuaternionLayout> layout = layoutOf(m)) {
            events_.attitude(*t, wire::attitudeOf(m, *layout), wire::specificForceOf(m));
          }
          if (!options_.no_gnss) {  // ArduPilot goes silent when its GPS does: the IMU's time tells how long
            const std::lock_guard<std::mutex> lock(gnss_mutex_);
            if (const auto g = navsat_.onVehicleTime(*t)) events_.gnss(*g);
          }
        });
  }

  bool readsCommands() const override { return cmd_vel_.matched() > 0; }
  bool attitudeMatched() const override { return imu_reader_.matched() > 0; }
  bool requestsMatched() const override {
    return arm_request_.matched() > 0 && mode_request_.matched() > 0 && arm_reply_.matched() > 0 &&
           mode_reply_.matched() > 0;
  }

  void sendOdometry(const autopilot::Odometry& o, const px4::Quaternion& attitude) override {
    if (!tf_) return;
    tf2_msgs::msg::TFMessage m = wire::externalOdometry(o, attitude);
    tf_.write(m);
  }
  std::string odometryTopic() const override { return topics::apTopic(ns_, "tf"); }
  std::string odometryHint() const override {
    return "set VISO_TYPE = 1, EK3_SRC2_POSXY = 6 with EK3_SRC2_POSZ = 1, and switch to source set 2 when GPS is "
           "lost (RC function 90 or the source-switching Lua script); VISO_DELAY_MS = 50 (deploy/README.md, "
           "\"External odometry\")";
  }

  void send(const autopilot::Outbox& out) override {
    if (out.setpoint) {
      geometry_msgs::msg::TwistStamped m = wire::cmdVel(*out.setpoint);
      cmd_vel_.write(m);
    }
    if (out.request == autopilot::VehicleRequest::kArm && arm_request_) {
      srv::ArmMotors_Request m;
      m.arm(true);
      remember(arm_request_.writeRequest(m, arm_reply_.guid()));
    } else if (out.request == autopilot::VehicleRequest::kControlMode && mode_request_) {
      srv::ModeSwitch_Request m;
      m.mode(ardupilot::kModeGuided);
      remember(mode_request_.writeRequest(m, mode_reply_.guid()));
    }
  }

  std::string description() const override {
    const std::string order = options_.ap_quaternion ? ardupilot::quaternionLayoutName(*options_.ap_quaternion)
                                                     : "the quaternion order gravity tells";
    return "ArduPilot namespace '" + ns_ + "' (" + topics::apTopic(ns_, "imu/experimental/data") + " read as " + order +
           ", " + topics::apTopic(ns_, "status") + ")";
  }
  std::string commandTopic() const override { return topics::apTopic(ns_, "cmd_vel"); }
  std::string noReaderHint() const override {
    return "is ArduPilot's DDS client (DDS_ENABLE 1) connected to a Micro XRCE-DDS agent on this domain, with its "
           "topics under '" +
           ns_ + "' (DDS_USE_NS 1 puts them under ap/v<MAV_SYSID>; without it, --ap-namespace ap)?";
  }
  std::string noStatusHint() const override {
    return "no " + topics::apTopic(ns_, "status") +
           ": ArduPilot releases before the status message (Copter 4.6) "
           "do not send it; --engage needs it";
  }

 private:
  // The IMU quaternion's field order: --ap-quaternion, or once gravity has told it (auto); nothing is forwarded before.
  // On the IMU reader's thread only.
  std::optional<ardupilot::QuaternionLayout> layoutOf(const sensor_msgs::msg::Imu& m) {
    if (options_.ap_quaternion) return options_.ap_quaternion;
    const bool was_decided = order_.decided().has_value();
    const std::optional<ardupilot::QuaternionLayout> layout =
        order_.onSample(wire::orientationFieldsOf(m), wire::specificForceOf(m), disarmed_);
    if (layout && !was_decided) {
      events_.log(std::string("the IMU quaternion is in ") +
                  (*layout == ardupilot::QuaternionLayout::kRos ? "the ROS order (x, y, z, w)"
                                                                : "the order w, x, y, z (AP_DDS of 2024)") +
                  ": gravity agreed on " + std::to_string(order_.votes()) + " samples of " +
                  std::to_string(order_.samples()) + "; forwarding the attitude (--ap-quaternion " +
                  ardupilot::quaternionLayoutName(*layout) + " fixes it)");
    } else if (!layout && order_.samples() == kOrderHintSamples) {
      events_.log("the IMU quaternion's field order is not decided after " + std::to_string(kOrderHintSamples) +
                  " samples, so no attitude is forwarded: it is told only while the vehicle reports itself disarmed "
                  "(ArduPilot's status) and still; turn it if it faces north or south (there both orders look "
                  "level); in flight, or without a status, pass --ap-quaternion ros|wxyz");
    }
    return layout;
  }
  static constexpr std::uint64_t kOrderHintSamples = 500;  // 2.5 to 5 s of ArduPilot's IMU stream

  // Replies name their request; another client's requests on the same service get replies too.
  bool isOurs(const dds::SampleIds& ids) {
    const std::lock_guard<std::mutex> lock(requests_mutex_);
    for (const dds::SampleId& r : requests_) {
      if (r == ids.related) return true;
    }
    return false;
  }
  void remember(const std::optional<dds::SampleId>& id) {
    if (!id) return;
    const std::lock_guard<std::mutex> lock(requests_mutex_);
    requests_[next_++ % requests_.size()] = *id;
  }

  const BridgeOptions options_;
  const std::string ns_;
  const VehicleEvents events_;

  std::atomic<std::uint64_t> bad_stamps_{0};
  ardupilot::QuaternionOrderFinder order_;  // --ap-quaternion auto
  std::atomic<bool> disarmed_{false};       // the status says so (no status yet: not known to be on the ground)
  std::mutex gnss_mutex_;                   // the fixes and the IMU's time arrive on two readers (two threads)
  ardupilot::NavSatForward navsat_;
  std::mutex requests_mutex_;
  std::array<dds::SampleId, 8> requests_{};  // the newest requests sent
  std::size_t next_ = 0;

  dds::Writer<geometry_msgs::msg::TwistStamped> cmd_vel_;
  dds::Writer<tf2_msgs::msg::TFMessage> tf_;           // not with --odometry off
  dds::Writer<srv::ArmMotors_Request> arm_request_;    // --engage only
  dds::Writer<srv::ModeSwitch_Request> mode_request_;  // --engage only
  dds::Reader<srv::ArmMotors_Response> arm_reply_;
  dds::Reader<srv::ModeSwitch_Response> mode_reply_;
  dds::Reader<ardupilot_msgs::msg::Status> status_reader_;
  dds::Reader<sensor_msgs::msg::Imu> imu_reader_;
  dds::Reader<sensor_msgs::msg::NavSatFix> navsat_reader_;  // not with --no-gnss
};

}  // namespace

std::unique_ptr<VehicleLink> makeArdupilotLink(const BridgeOptions& options, VehicleEvents events) {
  return std::make_unique<ArdupilotLink>(options, std::move(events));
}

}  // namespace swa::bridge_node

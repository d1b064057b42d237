#pragma once
// The autopilot's side of swa_px4_bridge over DDS, one implementation per autopilot (px4_link.cpp,
// ardupilot_link.cpp): its endpoints, what arrives on them turned into the bridge core's terms (swa/autopilot/
// bridge_core.h), and the core's outbox turned into the autopilot's messages. The node (bridge_node.h) owns the core,
// the agent's side and the rules; a link keeps no state of the control loop.

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "bridge_options.h"
#include "swa/agent/samples.h"
#include "swa/autopilot/bridge_core.h"
#include "swa/autopilot/odometry_feed.h"
#include "swa/autopilot/quaternion_order.h"
#include "swa/dds/participant.h"
#include "swa/px4/gnss.h"

namespace swa::bridge_node {

// What a link reports, on the middleware's threads (the node serialises them).
struct VehicleEvents {
  // The attitude, with the accelerometer's specific force read at the same time when the vehicle gives one (PX4:
  // sensor_combined; ArduPilot: the same IMU message), FRD body, m/s^2.
  std::function<void(std::uint64_t timestamp_us, const px4::Quaternion& attitude,
                     const std::optional<ardupilot::SpecificForce>& force_frd)>
      attitude;
  std::function<void(bool armed, std::uint8_t mode)> status;
  std::function<void(const agent::GnssSample& gnss)> gnss;  // the vehicle's fix, in SWA's terms (PX4 only so far)
  std::function<void(const std::string& line)> log;         // an answer to a request, for the log
  // The vehicle's estimator says it has no aiding (PX4: vehicle_local_position.dead_reckoning, read with GNSS
  // forwarding; ArduPilot: the EKF failsafe in its status): with odometry fed, it is not fusing it.
  std::function<void(bool unaided)> estimator;
};

class VehicleLink {
 public:
  virtual ~VehicleLink() = default;
  // Creates the vehicle's endpoints on `p`; their callbacks call the events given at construction. Throws DdsError.
  virtual void connect(dds::Participant& p) = 0;
  // The vehicle reads what the bridge writes (every reader of the command stream matched).
  virtual bool readsCommands() const = 0;
  // The bridge hears the vehicle's attitude (its writer matched).
  virtual bool attitudeMatched() const = 0;
  // With --engage: the requests (arm, mode) reach the vehicle (ArduPilot: and its answers come back).
  virtual bool requestsMatched() const = 0;
  virtual void send(const autopilot::Outbox& out) = 0;
  // The agent's estimate as the autopilot's external odometry (PX4: vehicle_visual_odometry; ArduPilot: ap/tf, which
  // also carries the vehicle's own attitude).
  virtual void sendOdometry(const autopilot::Odometry& o, const px4::Quaternion& attitude) = 0;
  virtual std::string odometryTopic() const = 0;
  // What to set on the vehicle when it does not fuse the odometry (the pre-flight table, for the log).
  virtual std::string odometryHint() const = 0;

  // What became of the vehicle's GNSS reports, for the final counts and the summary (PX4's; nullopt: not forwarded
  // from this vehicle).
  virtual std::optional<px4::GnssForwardCounters> gnssCounters() const { return std::nullopt; }

  // For the log.
  virtual std::string description() const = 0;   // the autopilot, its namespace and topics
  virtual std::string commandTopic() const = 0;  // where the stream goes
  virtual std::string noReaderHint() const = 0;  // nothing reads the stream after 5 s
  virtual std::string noStatusHint() const = 0;  // attitude but no state after 5 s
};

std::unique_ptr<VehicleLink> makePx4Link(const BridgeOptions& options, VehicleEvents events);
std::unique_ptr<VehicleLink> makeArdupilotLink(const BridgeOptions& options, VehicleEvents events);

}  // namespace swa::bridge_node

#pragma once
// Each UAV's sensor samples on the wire, the bulk of the simulator's writers: a step's samples in one SensorFrame per
// UAV or each on its own topic, their sequence numbers, and the step once more after a reconnection. Apart from
// sim_ports.h, which owns the participant these writers live on and re-creates them with it.

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <swa/msg/Detections.h>
#include <swa/msg/GnssFix.h>
#include <swa/msg/Imu.h>
#include <swa/msg/SensorFrame.h>
#include <swa/ros/Detection3DArray.h>
#include <swa/ros/PoseWithCovarianceArrayStamped.h>

#include "autopilot_vehicles.h"
#include "latency_stats.h"
#include "port_clock.h"
#include "sim_summary.h"
#include "swa/dds/participant.h"
#include "swa/sim/scenario.h"
#include "swa/sim/world.h"

namespace swa::sim_node {

class SensorPorts {
 public:
  using Clock = PortClock;

  SensorPorts(const sim::Scenario& scenario, const sim::World& world, SimSummary& summary);

  // The writers are re-created with their participant: clear() drops the old ones, useFrames() says how the new
  // ones send (frames or a topic per sample), then addUav() creates each UAV's.
  void clear();
  void useFrames(bool frames) { frames_ = frames; }
  void addUav(dds::Participant& participant, int i, bool autopilot, bool own_gnss);
  // With vehicle.interface = px4 or ardupilot: the stand-ins that take the attitude (and the GNSS fix without
  // the simulator's own GNSS writers).
  void attach(AutopilotVehicles* autopilot) { autopilot_ = autopilot; }
  // UAV i's sensor endpoints without a reader, readable, e.g. "swa/uav2/imu (no reader)".
  void unmatched(int i, std::vector<std::string>& missing) const;

  // The step's samples of every UAV; `latency` (nullptr while not timed) records each IMU sample published. The
  // rest as SimPorts::publishSensors.
  std::vector<std::optional<agent::StampNs>> publish(std::optional<Clock::time_point> due,
                                                     CommandLatencyTracker* latency);
  void resend(int uav);  // the current step's samples of `uav` again, same sequence numbers

  bool sideWritten(int uav) const { return side_written_[static_cast<std::size_t>(uav)]; }
  bool detectionsAcknowledged(int uav, double wait_s);
  bool gnssAcknowledged(int uav, double wait_s);

 private:
  const sim::Scenario& scenario_;
  const sim::World& world_;
  SimSummary& summary_;
  AutopilotVehicles* autopilot_ = nullptr;
  std::vector<std::uint32_t> imu_seq_, det_seq_, gnss_seq_;
  std::vector<bool> side_written_;
  std::vector<dds::Writer<msg::Imu>> imu_;
  // Direct vehicles, SWA's own detections and the SWA naming: each step's samples of a UAV in one message
  // (idl/SensorFrame.idl) on swa/uav<i>/sensors, instead of imu_, det_ and gnss_.
  bool frames_ = false;
  std::vector<dds::Writer<msg::SensorFrame>> frame_;
  std::vector<std::uint32_t> frame_seq_;
  // The detections in the message the agents read (agent sensor.input): one of these three per UAV.
  std::vector<dds::Writer<msg::Detections>> det_;
  std::vector<dds::Writer<vision_msgs::msg::Detection3DArray>> vision_det_;
  std::vector<dds::Writer<mrs_msgs::msg::PoseWithCovarianceArrayStamped>> uvdar_det_;
  int detectionsMatched(std::size_t k) const;
  // Without frames: UAV i's writers of its sample topics (detections in the agents' type, GNSS if the simulator
  // reports it, IMU unless an autopilot stand-in does).
  void makeSampleWriters(dds::Participant& participant, int i, bool autopilot, bool own_gnss);
  // frames_: UAV k's samples of this step in one message; false if it has none or the write failed (counted).
  bool writeFrame(std::size_t k, const sim::UavSensors& s, std::optional<WallNs> due_ns,
                  CommandLatencyTracker* latency);
  bool writeDetections(std::size_t k, const agent::DetectionSet& s, std::uint32_t seq);
  std::vector<dds::Writer<msg::GnssFix>> gnss_;
};

}  // namespace swa::sim_node

// SensorPorts (sensor_ports.h): the writers of each UAV's samples and what goes out on them each step, kept apart from
// the participant's life (sim_ports.cpp) and the world's topics (world_ports.cpp).
#include "sensor_ports.h"

#include <swa/msg/DetectionsPubSubTypes.h>
#include <swa/msg/GnssFixPubSubTypes.h>
#include <swa/msg/ImuPubSubTypes.h>
#include <swa/msg/SensorFramePubSubTypes.h>
#include <swa/ros/Detection3DArrayPubSubTypes.h>
#include <swa/ros/PoseWithCovarianceArrayStampedPubSubTypes.h>

#include "swa/dds/qos_profiles.h"
#include "swa/dds/topics.h"
#include "swa/wire/ros_detections.h"
#include "swa/wire/samples.h"

namespace swa::sim_node {

SensorPorts::SensorPorts(const sim::Scenario& scenario, const sim::World& world, SimSummary& summary)
    : scenario_(scenario),
      world_(world),
      summary_(summary),
      imu_seq_(static_cast<std::size_t>(world.uav_count()), 0),
      det_seq_(static_cast<std::size_t>(world.uav_count()), 0),
      gnss_seq_(static_cast<std::size_t>(world.uav_count()), 0),
      side_written_(static_cast<std::size_t>(world.uav_count()), false) {}

void SensorPorts::clear() {
  frame_.clear();
  det_.clear();
  vision_det_.clear();
  uvdar_det_.clear();
  gnss_.clear();
  imu_.clear();
}

void SensorPorts::addUav(dds::Participant& participant, int i, bool autopilot, bool own_gnss) {
  // In realtime a lost sample is repaired sooner, since it holds back the later ones (profiles.xml,
  // swa_frame_writer_realtime); lockstep keeps the cheaper heartbeat.
  const bool realtime = scenario_.clock.mode == sim::ClockMode::kRealtime;
  if (frames_) {
    frame_.push_back(participant.writer<msg::SensorFramePubSubType>(
        dds::topics::sensors(i), realtime ? dds::qos::kFrameWriterRealtime : dds::qos::kFrameWriter));
    if (frame_seq_.size() < frame_.size()) frame_seq_.push_back(0);
  } else {
    makeSampleWriters(participant, i, autopilot, own_gnss);
  }
}

void SensorPorts::makeSampleWriters(dds::Participant& participant, int i, bool autopilot, bool own_gnss) {
  switch (scenario_.agent.sensor.input) {
    case agent::DetectionInput::kSwa:
      det_.push_back(
          participant.writer<msg::DetectionsPubSubType>(dds::topics::detections(i), dds::qos::kDetectionsGnssWriter));
      break;
    case agent::DetectionInput::kVisionMsgs:
      vision_det_.push_back(participant.writer<vision_msgs::msg::Detection3DArrayPubSubType>(
          dds::topics::visionDetections(i), dds::qos::kDetectionsGnssWriter));
      break;
    case agent::DetectionInput::kUvdar:
      uvdar_det_.push_back(participant.writer<mrs_msgs::msg::PoseWithCovarianceArrayStampedPubSubType>(
          dds::topics::uvdarPoses(i), dds::qos::kDetectionsGnssWriter));
      break;
  }
  gnss_.push_back(
      own_gnss ? participant.writer<msg::GnssFixPubSubType>(dds::topics::gnss(i), dds::qos::kDetectionsGnssWriter)
               : dds::Writer<msg::GnssFix>());
  // With an autopilot its stand-in writes the attitude the bridge turns into swa/uav<i>/imu.
  if (!autopilot) {
    imu_.push_back(participant.writer<msg::ImuPubSubType>(
        dds::topics::imu(i),
        scenario_.clock.mode == sim::ClockMode::kRealtime ? dds::qos::kSensorWriterRealtime : dds::qos::kSensorWriter));
  }
}

void SensorPorts::unmatched(int i, std::vector<std::string>& missing) const {
  const auto k = static_cast<std::size_t>(i);
  if (frames_) {
    if (frame_[k].matched() < 1) missing.push_back(dds::topics::sensors(i) + " (no reader)");
    return;
  }
  if (detectionsMatched(k) < 1) {
    const std::string topic = !det_.empty()          ? dds::topics::detections(i)
                              : !vision_det_.empty() ? dds::topics::visionDetections(i)
                                                     : dds::topics::uvdarPoses(i);
    missing.push_back(topic + " (no reader)");
  }
  if (gnss_[k] && gnss_[k].matched() < 1) missing.push_back(dds::topics::gnss(i) + " (no reader)");
  // No IMU writers with an autopilot: its stand-in's endpoints are its own (AutopilotVehicles::unmatched).
  if (!imu_.empty() && imu_[k].matched() < 1) missing.push_back(dds::topics::imu(i) + " (no reader)");
}

std::vector<std::optional<agent::StampNs>> SensorPorts::publish(std::optional<Clock::time_point> due,
                                                                CommandLatencyTracker* latency) {
  const std::optional<WallNs> due_ns = due ? std::optional<WallNs>(wallNs(*due)) : std::nullopt;
  const auto n = static_cast<std::size_t>(world_.uav_count());
  std::vector<std::optional<agent::StampNs>> imu_stamps(n);
  const std::vector<sim::UavSensors>& sensors = world_.sensors();
  const auto writeSides = [&](std::size_t k) {
    const sim::UavSensors& s = sensors[k];
    side_written_[k] = s.detections.has_value() || s.gnss.has_value();
    if (s.detections && !writeDetections(k, *s.detections, ++det_seq_[k])) ++summary_.write_failures;
    if (s.gnss && gnss_[k]) {
      msg::GnssFix m = wire::toMsg(*s.gnss, static_cast<std::uint32_t>(k), ++gnss_seq_[k]);
      if (!gnss_[k].write(m)) ++summary_.write_failures;
    } else if (s.gnss && autopilot_ && !autopilot_->publishGnss(static_cast<int>(k), *s.gnss)) {
      ++summary_.write_failures;
    }
  };
  const auto writeImu = [&](std::size_t k) {
    const sim::UavSensors& s = sensors[k];
    if (!s.imu) return;
    msg::Imu m = wire::toMsg(*s.imu, static_cast<std::uint32_t>(k), ++imu_seq_[k]);
    const WallNs published_ns = wallNs(Clock::now());
    if (autopilot_ ? autopilot_->publishAttitude(static_cast<int>(k), *s.imu, imu_seq_[k]) : imu_[k].write(m)) {
      if (latency) latency->published(static_cast<int>(k), imu_seq_[k], s.imu->stamp_ns, published_ns, due_ns);
      imu_stamps[k] = s.imu->stamp_ns;
    } else {
      ++summary_.write_failures;
    }
  };
  if (frames_) {
    // One message per UAV: its parts arrive together and in order, so the lockstep simulator waits for no
    // acknowledgment (side_written_ stays false) and realtime needs no IMU-first order.
    for (std::size_t k = 0; k < n; ++k) {
      if (writeFrame(k, sensors[k], due_ns, latency))
        imu_stamps[k] = sensors[k].imu ? std::optional(sensors[k].imu->stamp_ns) : std::nullopt;
    }
    return imu_stamps;
  }
  if (due) {
    // Realtime: every UAV's IMU sample first, the detections and GNSS fixes after them. The command answers the IMU
    // sample alone, so neither the simulator's writing of the others nor the agent's receiving of them comes before
    // it; at 64 UAVs a step with detections wrote 128 other samples before the last IMU sample. An agent processes
    // a step's samples in the closed loop's order whatever their arrival order (agent_samples.cpp).
    for (std::size_t k = 0; k < n; ++k) writeImu(k);
    for (std::size_t k = 0; k < n; ++k) writeSides(k);
    return imu_stamps;
  }
  // Lockstep (and realtime's untimed step 0): detections and GNSS before the IMU sample. The agent publishes its
  // state of the step once its inputs fall quiet (agent_node.cpp). Arriving after the IMU sample, the step's
  // detections could come after that on a host where a process waits 100 ms for the CPU (measured: 128 UAV processes
  // in lockstep on 2 cores, some agents' states without that step's detections, NEES no longer equal to swa_batch's);
  // arriving before it, they are held and processed with it, at once.
  for (std::size_t k = 0; k < n; ++k) {
    writeSides(k);
    writeImu(k);
  }
  return imu_stamps;
}

void SensorPorts::resend(int uav) {
  // The same samples with the same sequence numbers: an agent that has them drops the copy (not newer), one that
  // never got them answers now.
  const auto k = static_cast<std::size_t>(uav);
  const sim::UavSensors& s = world_.sensors()[k];
  const auto id = static_cast<std::uint32_t>(k);
  bool written = true;
  if (frames_) {
    if (!s.imu && !s.detections && !s.gnss) return;
    msg::SensorFrame m;
    m.uav_id(id);
    m.header().stamp_ns(world_.time_ns());
    m.header().seq(frame_seq_[k]);
    if (s.detections) m.detection_set().push_back(wire::toMsg(*s.detections, id, det_seq_[k]));
    if (s.gnss) m.gnss_fix().push_back(wire::toMsg(*s.gnss, id, gnss_seq_[k]));
    if (s.imu) m.imu_sample().push_back(wire::toMsg(*s.imu, id, imu_seq_[k]));
    written = frame_[k].write(m);
  } else {
    if (s.detections) written = writeDetections(k, *s.detections, det_seq_[k]) && written;
    if (s.gnss && gnss_[k]) {
      msg::GnssFix m = wire::toMsg(*s.gnss, id, gnss_seq_[k]);
      written = gnss_[k].write(m) && written;
    }
    if (s.imu) {
      msg::Imu m = wire::toMsg(*s.imu, id, imu_seq_[k]);
      written = imu_[k].write(m) && written;
    }
  }
  if (!written) ++summary_.write_failures;
  ++summary_.resent_after_reconnection;
}

bool SensorPorts::detectionsAcknowledged(int uav, double wait_s) {
  const auto k = static_cast<std::size_t>(uav);
  if (!det_.empty()) return det_[k].waitForAcknowledgments(wait_s);
  if (!vision_det_.empty()) return vision_det_[k].waitForAcknowledgments(wait_s);
  return uvdar_det_[k].waitForAcknowledgments(wait_s);
}

int SensorPorts::detectionsMatched(std::size_t k) const {
  if (!det_.empty()) return det_[k].matched();
  if (!vision_det_.empty()) return vision_det_[k].matched();
  return uvdar_det_[k].matched();
}

bool SensorPorts::writeDetections(std::size_t k, const agent::DetectionSet& s, std::uint32_t seq) {
  const auto id = static_cast<std::uint32_t>(k);
  if (!det_.empty()) {
    msg::Detections m = wire::toMsg(s, id, seq);
    return det_[k].write(m);
  }
  if (!vision_det_.empty()) {
    vision_msgs::msg::Detection3DArray m = wire::detection3DArray(s, id);
    return vision_det_[k].write(m);
  }
  mrs_msgs::msg::PoseWithCovarianceArrayStamped m = wire::poseArray(s, id);
  return uvdar_det_[k].write(m);
}

bool SensorPorts::writeFrame(std::size_t k, const sim::UavSensors& s, std::optional<WallNs> due_ns,
                             CommandLatencyTracker* latency) {
  if (!s.imu && !s.detections && !s.gnss) return false;
  const auto id = static_cast<std::uint32_t>(k);
  msg::SensorFrame m;
  m.uav_id(id);
  m.header().stamp_ns(world_.time_ns());
  m.header().seq(++frame_seq_[k]);
  if (s.detections) m.detection_set().push_back(wire::toMsg(*s.detections, id, ++det_seq_[k]));
  if (s.gnss) m.gnss_fix().push_back(wire::toMsg(*s.gnss, id, ++gnss_seq_[k]));
  if (s.imu) m.imu_sample().push_back(wire::toMsg(*s.imu, id, ++imu_seq_[k]));
  const WallNs published_ns = wallNs(Clock::now());
  if (!frame_[k].write(m)) {
    ++summary_.write_failures;
    return false;
  }
  if (s.imu && latency) latency->published(static_cast<int>(k), imu_seq_[k], s.imu->stamp_ns, published_ns, due_ns);
  return true;
}

bool SensorPorts::gnssAcknowledged(int uav, double wait_s) {
  // GNSS through the autopilot is best effort, as PX4's topics are: nothing to wait for.
  dds::Writer<msg::GnssFix>& w = gnss_[static_cast<std::size_t>(uav)];
  return !w || w.waitForAcknowledgments(wait_s);
}

}  // namespace swa::sim_node

#include "sim_ports.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iomanip>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>

#include <swa/msg/ClockPubSubTypes.h>
#include <swa/msg/DetectionsPubSubTypes.h>
#include <swa/msg/GnssFixPubSubTypes.h>
#include <swa/msg/ImuPubSubTypes.h>
#include <swa/msg/ScenarioEventPubSubTypes.h>
#include <swa/msg/SensorFramePubSubTypes.h>
#include <swa/msg/SwarmTruthPubSubTypes.h>
#include <swa/msg/VelocitySetpointPubSubTypes.h>
#include <swa/ros/Detection3DArrayPubSubTypes.h>
#include <swa/ros/PoseWithCovarianceArrayStampedPubSubTypes.h>

#include "swa/dds/qos_profiles.h"
#include "swa/dds/topics.h"
#include "swa/sim/timing.h"
#include "swa/wire/ros_detections.h"
#include "swa/wire/samples.h"
#include "swa/wire/world.h"
#include "world_command.h"

namespace swa::sim_node {
namespace {

// A UAV's commands may come from another writer once its current one has been silent this long (command_gate.h):
// longer than any pause of a healthy agent (it answers every 10 ms), shorter than the launcher's restart of a crashed
// one (0.5 s back-off plus the start).
constexpr auto kCommandHandover = std::chrono::milliseconds(500);

// SWA_SENSOR_FRAMES (deploy/README.md): 1 or unset, a step's samples in one message where the agents read them
// (SensorFrame); 0, each on its own topic, as bridges and real sensors send them.
bool framesAllowed() {
  const char* v = std::getenv("SWA_SENSOR_FRAMES");
  if (v == nullptr || std::string(v) == "1") return true;
  if (std::string(v) == "0") return false;
  throw std::runtime_error("SWA_SENSOR_FRAMES must be 0 or 1, not '" + std::string(v) + "'");
}

}  // namespace

SimPorts::SimPorts(const sim::Scenario& scenario, const SimOptions& options, sim::World& world, SimSummary& summary,
                   const std::atomic<bool>& stop, int domain_id, const std::string& profiles_file)
    : scenario_(scenario),
      options_(options),
      world_(world),
      summary_(summary),
      stop_(stop),
      n_(world.uav_count()),
      gate_(n_, kCommandHandover),
      latency_(n_),
      imu_seq_(static_cast<std::size_t>(n_), 0),
      det_seq_(static_cast<std::size_t>(n_), 0),
      gnss_seq_(static_cast<std::size_t>(n_), 0),
      side_written_(static_cast<std::size_t>(n_), false),
      refused_(static_cast<std::size_t>(n_)),
      profiles_file_(profiles_file) {
  if (!options_.truth_out.empty()) {
    truth_csv_.open(options_.truth_out);
    if (!truth_csv_) throw std::runtime_error("cannot write --truth-out " + options_.truth_out);
    truth_csv_ << "step,t_ns,uav,x_m,y_m,vx_mps,vy_mps,ax_mps2,ay_mps2,heading_rad,agent_alive,gnss_valid,failsafe\n";
    truth_csv_ << std::setprecision(17);
  }

  frames_allowed_ = framesAllowed();  // a bad value stops the simulator before it joins the domain
  connect(domain_id, profiles_file);
  sayPorts();
  if (scenario.vehicle.interface == sim::VehicleInterface::kPx4) {
    autopilot_ = std::make_unique<Px4Vehicles>(*participant_, n_, scenario.vehicle, scenario.imu.source);
  } else if (scenario.vehicle.interface == sim::VehicleInterface::kArdupilot) {
    autopilot_ = std::make_unique<ArdupilotVehicles>(*participant_, n_, scenario.vehicle, scenario.imu.source);
  }
}

void SimPorts::sayPorts() {
  if (const std::vector<int> ports = dds::Participant::ownSharedMemoryPorts(); !ports.empty()) {
    std::string list;
    for (const int port : ports) list += " " + std::to_string(port);
    std::fprintf(stderr, "swa_sim: listening on shared-memory ports%s\n", list.c_str());
  }
}

void SimPorts::connect(int domain_id, const std::string& profiles_file) {
  participant_ = std::make_unique<dds::Participant>("swa_sim", domain_id, profiles_file);
  events_ = participant_->writer<msg::ScenarioEventPubSubType>(dds::topics::kEvents, dds::qos::kEventWriter);
  truth_ = participant_->writer<msg::SwarmTruthPubSubType>(dds::topics::kTruth, dds::qos::kTruthWriter);
  clock_ = participant_->writer<msg::ClockPubSubType>(dds::topics::kClock, dds::qos::kClockWriter);
  const bool autopilot = scenario_.vehicle.interface != sim::VehicleInterface::kDirect;
  // With GNSS from the autopilot the bridges write swa/uav<i>/gnss; the simulator reports the fix as PX4 does.
  const bool own_gnss = !autopilot || scenario_.vehicle.gnss_source == sim::GnssSource::kSwa;
  // In realtime a lost sample is repaired sooner, since it holds back the later ones (profiles.xml,
  // swa_frame_writer_realtime); lockstep keeps the cheaper heartbeat.
  const bool realtime = scenario_.clock.mode == sim::ClockMode::kRealtime;
  // In the ros2 naming each sample keeps its own topic, where ROS tools expect them.
  frames_ = frames_allowed_ && !autopilot && scenario_.agent.sensor.input == agent::DetectionInput::kSwa &&
            participant_->wireNames().naming == dds::Naming::kSwa;
  for (int i = 0; i < n_; ++i) {
    if (frames_) {
      frame_.push_back(participant_->writer<msg::SensorFramePubSubType>(
          dds::topics::sensors(i), realtime ? dds::qos::kFrameWriterRealtime : dds::qos::kFrameWriter));
      if (frame_seq_.size() < frame_.size()) frame_seq_.push_back(0);
    } else {
      makeSampleWriters(i, autopilot, own_gnss);
    }
    if (autopilot) continue;
    cmd_.push_back(participant_->readerWithOrigin<msg::VelocitySetpointPubSubType>(
        dds::topics::cmdVel(i), dds::qos::kCommandReader,
        [this, i](msg::VelocitySetpoint&& m, const dds::WriterGuid& w) {
          queue_.push(Answer{i, std::move(m), Clock::now(), w, true});
        }));
  }
}

void SimPorts::makeSampleWriters(int i, bool autopilot, bool own_gnss) {
  switch (scenario_.agent.sensor.input) {
    case agent::DetectionInput::kSwa:
      det_.push_back(
          participant_->writer<msg::DetectionsPubSubType>(dds::topics::detections(i), dds::qos::kDetectionsGnssWriter));
      break;
    case agent::DetectionInput::kVisionMsgs:
      vision_det_.push_back(participant_->writer<vision_msgs::msg::Detection3DArrayPubSubType>(
          dds::topics::visionDetections(i), dds::qos::kDetectionsGnssWriter));
      break;
    case agent::DetectionInput::kUvdar:
      uvdar_det_.push_back(participant_->writer<mrs_msgs::msg::PoseWithCovarianceArrayStampedPubSubType>(
          dds::topics::uvdarPoses(i), dds::qos::kDetectionsGnssWriter));
      break;
  }
  gnss_.push_back(
      own_gnss ? participant_->writer<msg::GnssFixPubSubType>(dds::topics::gnss(i), dds::qos::kDetectionsGnssWriter)
               : dds::Writer<msg::GnssFix>());
  // With an autopilot its stand-in writes the attitude the bridge turns into swa/uav<i>/imu.
  if (!autopilot) {
    imu_.push_back(participant_->writer<msg::ImuPubSubType>(
        dds::topics::imu(i),
        scenario_.clock.mode == sim::ClockMode::kRealtime ? dds::qos::kSensorWriterRealtime : dds::qos::kSensorWriter));
  }
}

SimPorts::~SimPorts() {
  participant_.reset();  // first: no listener runs any more
  autopilot_.reset();
}

bool SimPorts::awaitDiscovery() {
  const auto t0 = Clock::now();
  const auto deadline = t0 + seconds(options_.startup_timeout_s);
  std::fprintf(stderr, "swa_sim: waiting for %d agent(s) on domain %d (startup timeout %.0f s)\n", n_,
               participant_->domainId(), options_.startup_timeout_s);
  std::vector<std::string> missing;
  while (!stop_) {
    if (olderTwinRuns()) return false;
    missing = unmatchedEndpoints();
    if (missing.empty()) {
      summary_.discovery_s = secondsSince(t0);
      std::fprintf(stderr, "swa_sim: all %d agent(s) discovered in %.2f s\n", n_, summary_.discovery_s);
      return true;
    }
    if (Clock::now() >= deadline) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  if (stop_) return false;
  std::ostringstream list;
  for (std::size_t k = 0; k < missing.size() && k < 12; ++k) list << "\n  " << missing[k];
  if (missing.size() > 12) list << "\n  ... and " << missing.size() - 12 << " more";
  std::fprintf(stderr, "swa_sim: discovery incomplete after %.0f s; unmatched endpoints:%s\n",
               options_.startup_timeout_s, list.str().c_str());
  return false;
}

std::vector<std::string> SimPorts::unmatchedEndpoints() const {
  std::vector<std::string> missing;
  for (int i = 0; i < n_; ++i) {
    const auto k = static_cast<std::size_t>(i);
    if (frames_) {
      if (frame_[k].matched() < 1) missing.push_back(dds::topics::sensors(i) + " (no reader)");
      if (cmd_[k].matched() < 1) missing.push_back(dds::topics::cmdVel(i) + " (no writer)");
      continue;
    }
    if (detectionsMatched(k) < 1) {
      const std::string topic = !det_.empty()          ? dds::topics::detections(i)
                                : !vision_det_.empty() ? dds::topics::visionDetections(i)
                                                       : dds::topics::uvdarPoses(i);
      missing.push_back(topic + " (no reader)");
    }
    if (gnss_[k] && gnss_[k].matched() < 1) missing.push_back(dds::topics::gnss(i) + " (no reader)");
    if (autopilot_) {
      autopilot_->unmatched(i, missing);
      continue;
    }
    if (imu_[k].matched() < 1) missing.push_back(dds::topics::imu(i) + " (no reader)");
    if (cmd_[k].matched() < 1) missing.push_back(dds::topics::cmdVel(i) + " (no writer)");
  }
  if (truth_.matched() < options_.wait_monitors) missing.push_back(std::string(dds::topics::kTruth) + " (monitor)");
  if (events_.matched() < options_.wait_monitors) missing.push_back(std::string(dds::topics::kEvents) + " (monitor)");
  return missing;
}

void SimPorts::healDeafness() {
  const Clock::time_point now = Clock::now();
  if (now < next_deafness_check_) return;
  next_deafness_check_ = now + kDeafnessCheckPeriod;
  std::vector<int> deaf;
  for (const int port : dds::Participant::deafSharedMemoryPorts()) {
    if (std::find(deaf_ports_.begin(), deaf_ports_.end(), port) == deaf_ports_.end()) deaf.push_back(port);
  }
  if (deaf.empty()) return;
  const double t_s = sim::stampSeconds(world_.time_ns());
  if (autopilot_) {
    // The stand-ins' endpoints live on this participant and their vehicles' state with them: not re-created.
    deaf_ports_.insert(deaf_ports_.end(), deaf.begin(), deaf.end());
    std::fprintf(stderr,
                 "swa_sim: t = %.2f s: deaf on shared-memory port %d: Fast DDS re-created /dev/shm/fastrtps_port%d "
                 "under this process (a peer judged it dead, e.g. while the simulator was stopped), so what the "
                 "bridges send to it is lost; with autopilot stand-ins the simulator does not re-create its "
                 "participant and the run cannot recover (deploy/README.md)\n",
                 t_s, deaf.front(), deaf.front());
    return;
  }
  ++summary_.reconnections;
  std::fprintf(stderr,
               "swa_sim: t = %.2f s: deaf on shared-memory port %d: Fast DDS re-created /dev/shm/fastrtps_port%d "
               "under this process (a peer judged it dead, e.g. while the simulator was stopped), so what agents send "
               "to it is lost: re-creating the participant (reconnection %d)\n",
               t_s, deaf.front(), deaf.front(), summary_.reconnections);
  reconnect();
}

void SimPorts::reconnect() {
  const int domain_id = participant_->domainId();
  participant_->abandonAcknowledgments();  // none can reach a deaf port
  frame_.clear();
  det_.clear();
  vision_det_.clear();
  uvdar_det_.clear();
  gnss_.clear();
  imu_.clear();
  cmd_.clear();
  participant_.reset();
  connect(domain_id, profiles_file_);
  sayPorts();
  // The new port files are healthy; a port of the same number found deaf later is a new deafness.
  deaf_ports_.clear();
  // What the old writers sent last may not have reached everyone before they were deleted: in lockstep, the agents
  // still waited for get the step's samples once more (repeatWhileWaiting).
  resend_after_reconnect_ = true;
  // Nothing steps until every endpoint matched again, so no answer is missed meanwhile: the drivers see the wait as
  // a stall of the simulator (swa/app/stall_watch.h) and blame no agent for it. The agents' command writers keep
  // their newest answer (TRANSIENT_LOCAL), which the new readers receive once matched.
  const auto t0 = Clock::now();
  std::vector<std::string> missing = unmatchedEndpoints();
  while (!stop_ && !missing.empty() && Clock::now() - t0 < kRematchTimeout) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    missing = unmatchedEndpoints();
  }
  if (missing.empty()) {
    std::fprintf(stderr, "swa_sim: every endpoint matched again %.2f s after re-creating the participant\n",
                 secondsSince(t0));
  } else if (!stop_) {
    std::fprintf(stderr,
                 "swa_sim: %zu endpoint(s) still unmatched %.0f s after re-creating the participant (first: "
                 "%s); the run goes on\n",
                 missing.size(), secondsSince(t0), missing.front().c_str());
  }
}

void SimPorts::stepTaken(Clock::time_point t) {
  if (time_latency_) latency_.stepTaken(wallNs(t));
}

void SimPorts::publishStepOutputs(const AliveFn& alive) {
  if (world_.step_index() % 10 == 0) noteYoungerTwin();
  for (const sim::Event& e : world_.events()) publishEvent(sim::eventOf(e));
  if (world_.step_index() % options_.truth_every == 0 || world_.finished()) publishTruth(alive);
  publishClock();
}

void SimPorts::publishClock() {
  const wire::ClockTick tick{static_cast<std::uint64_t>(world_.step_index()), world_.time_ns(),
                             sim::stepPeriodNs(scenario_.dynamics.rate_hz)};
  msg::Clock m = wire::toMsg(tick, ++clock_seq_);
  if (!clock_.write(m)) ++summary_.write_failures;
}

std::vector<std::optional<agent::StampNs>> SimPorts::publishSensors(std::optional<Clock::time_point> due) {
  resend_after_reconnect_ = false;  // a new step: its samples go out on the new writers
  const std::optional<WallNs> due_ns = due ? std::optional<WallNs>(wallNs(*due)) : std::nullopt;
  std::vector<std::optional<agent::StampNs>> imu_stamps(static_cast<std::size_t>(n_));
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
      if (time_latency_) latency_.published(static_cast<int>(k), imu_seq_[k], s.imu->stamp_ns, published_ns, due_ns);
      imu_stamps[k] = s.imu->stamp_ns;
    } else {
      ++summary_.write_failures;
    }
  };
  const auto n = static_cast<std::size_t>(n_);
  if (frames_) {
    // One message per UAV: its parts arrive together and in order, so the lockstep simulator waits for no
    // acknowledgment (side_written_ stays false) and realtime needs no IMU-first order.
    for (std::size_t k = 0; k < n; ++k) {
      if (writeFrame(k, sensors[k], due_ns))
        imu_stamps[k] = sensors[k].imu ? std::optional(sensors[k].imu->stamp_ns) : std::nullopt;
    }
    return imu_stamps;
  }
  if (due) {
    // Realtime: every UAV's IMU sample first, the detections and GNSS fixes after them. The command answers the IMU
    // sample alone, so neither the simulator's writing of the others nor the agent's receiving of them comes before
    // it; at 64 UAVs a step with detections wrote 128 other samples before the last IMU sample. An agent processes
    // a step's samples in the closed loop's order whatever their arrival order (agent_node.cpp).
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

void SimPorts::publishTruth(const AliveFn& alive) {
  last_truth_step_ = world_.step_index();
  wire::SwarmTruth truth{world_.time_ns(), world_.truth(), {}};
  for (const sim::UavTruth& t : truth.uavs) {
    truth.agent_alive.push_back(alive(t.id));
    if (truth_csv_.is_open()) {
      truth_csv_ << world_.step_index() << ',' << world_.time_ns() << ',' << t.id << ',' << t.position_m.x() << ','
                 << t.position_m.y() << ',' << t.velocity_mps.x() << ',' << t.velocity_mps.y() << ','
                 << t.acceleration_mps2.x() << ',' << t.acceleration_mps2.y() << ',' << t.heading_rad << ','
                 << (truth.agent_alive.back() ? 1 : 0) << ',' << (t.gnss_valid ? 1 : 0) << ',' << (t.failsafe ? 1 : 0)
                 << '\n';
    }
  }
  msg::SwarmTruth m = wire::toMsg(truth, ++truth_seq_);
  if (!truth_.write(m)) ++summary_.write_failures;
}

void SimPorts::publishEvent(const char* kind, int uav, double value, const std::string& text) {
  publishEvent({static_cast<double>(world_.time_ns()) * 1e-9, kind, uav, -1, value, text});
}

void SimPorts::publishEvent(const sim::EventRecord& event) {
  msg::ScenarioEvent m = wire::toMsg(event, ++event_seq_);
  if (!events_.write(m)) ++summary_.write_failures;
}

void SimPorts::publishEndBeforeStart(const std::string& why) {
  publishEvent(sim::event_kind::kScenarioEnd, sim::kAllUavs, 0.0, why);
  events_.waitForAcknowledgments(1.0);
}

void SimPorts::publishEnd(const AliveFn& alive, bool completed) {
  if (last_truth_step_ != world_.step_index()) publishTruth(alive);
  publishEvent(sim::event_kind::kScenarioEnd, sim::kAllUavs, 0.0, completed ? "completed" : "interrupted");
  // Give late readers of the last samples a moment; events are TRANSIENT_LOCAL anyway.
  events_.waitForAcknowledgments(2.0);
  truth_.waitForAcknowledgments(2.0);
  if (truth_csv_.is_open()) truth_csv_.flush();
}

void SimPorts::repeatWhileWaiting(const std::vector<int>& uavs) {
  if (autopilot_) {
    for (const int uav : uavs) autopilot_->repeatAttitude(uav);
    return;
  }
  if (!resend_after_reconnect_) return;
  resend_after_reconnect_ = false;
  for (const int uav : uavs) resendStep(uav);
}

void SimPorts::resendStep(int uav) {
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

void SimPorts::vehiclesStep() {
  if (!autopilot_) return;
  autopilot_->step(world_, [this](int uav, double value, const sim::StandinEvent& e) {
    std::fprintf(stderr, "swa_sim: t = %.2f s: UAV %d: %s\n", sim::stampSeconds(world_.time_ns()), uav, e.text.c_str());
    const char* kind = e.control == sim::StandinEvent::Control::kLost       ? sim::event_kind::kControlLost
                       : e.control == sim::StandinEvent::Control::kRegained ? sim::event_kind::kControlRegained
                                                                            : sim::event_kind::kFailsafe;
    publishEvent(kind, uav, value, e.text);
  });
}

void SimPorts::finishLatency(bool realtime, const LogHistogram& step_lag) {
  latency_.finish(wallNs(Clock::now()));
  summary_.latency = latency_.report();
  summary_.step_lag_p99_us = realtime ? step_lag.quantileNs(0.99) * 1e-3 : std::nan("");
  summary_.step_lag_max_us = realtime ? step_lag.maxNs() * 1e-3 : std::nan("");
}

bool SimPorts::detectionsAcknowledged(int uav, double wait_s) {
  const auto k = static_cast<std::size_t>(uav);
  if (!det_.empty()) return det_[k].waitForAcknowledgments(wait_s);
  if (!vision_det_.empty()) return vision_det_[k].waitForAcknowledgments(wait_s);
  return uvdar_det_[k].waitForAcknowledgments(wait_s);
}

int SimPorts::detectionsMatched(std::size_t k) const {
  if (!det_.empty()) return det_[k].matched();
  if (!vision_det_.empty()) return vision_det_[k].matched();
  return uvdar_det_[k].matched();
}

bool SimPorts::writeDetections(std::size_t k, const agent::DetectionSet& s, std::uint32_t seq) {
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

bool SimPorts::writeFrame(std::size_t k, const sim::UavSensors& s, std::optional<WallNs> due_ns) {
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
  if (s.imu && time_latency_) {
    latency_.published(static_cast<int>(k), imu_seq_[k], s.imu->stamp_ns, published_ns, due_ns);
  }
  return true;
}

bool SimPorts::gnssAcknowledged(int uav, double wait_s) {
  // GNSS through the autopilot is best effort, as PX4's topics are: nothing to wait for.
  dds::Writer<msg::GnssFix>& w = gnss_[static_cast<std::size_t>(uav)];
  return !w || w.waitForAcknowledgments(wait_s);
}

std::string SimPorts::commandTopic(int uav) const {
  return autopilot_ ? autopilot_->commandTopic(uav) : dds::topics::cmdVel(uav);
}

bool SimPorts::olderTwinRuns() {
  if (!participant_->mustGiveWay()) {
    noteYoungerTwin();
    return false;
  }
  const std::optional<dds::Peer> twin = participant_->twin();
  std::fprintf(stderr,
               "swa_sim: REFUSING to run: another swa_sim (pid %ld on host %s) was already running in %s on domain "
               "%d; two simulators would publish two worlds to the same agents. Stop it, or use another SWA_SWARM.\n",
               twin ? twin->card->pid : 0L, twin ? twin->card->host.c_str() : "?",
               twin && !twin->card->swarm.empty() ? ("swarm " + twin->card->swarm).c_str() : "the default swarm",
               participant_->domainId());
  summary_.refused_as_twin = true;
  return true;
}

void SimPorts::noteYoungerTwin() {
  const std::optional<dds::Peer> twin = participant_->twin();
  if (!twin || twin->key == reported_twin_) return;
  reported_twin_ = twin->key;
  std::fprintf(stderr,
               "swa_sim: a second swa_sim (pid %ld on host %s) joined this swarm; it started later and must "
               "refuse to run\n",
               twin->card->pid, twin->card->host.c_str());
}

}  // namespace swa::sim_node

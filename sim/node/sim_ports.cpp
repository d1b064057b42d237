// SimPorts (sim_ports.h): the participant's life (its endpoints created, awaited, a twin refused) and the steps' calls
// handed to the world's and the sensors' writers (world_ports.cpp, sensor_ports.cpp).
#include "sim_ports.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>

#include <swa/msg/VelocitySetpointPubSubTypes.h>

#include "swa/dds/qos_profiles.h"
#include "swa/dds/topics.h"
#include "swa/sim/timing.h"

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
      world_ports_(scenario, options, world, summary),
      sensors_(scenario, world, summary),
      refused_(static_cast<std::size_t>(n_)),
      profiles_file_(profiles_file) {
  frames_allowed_ = framesAllowed();  // a bad value stops the simulator before it joins the domain
  connect(domain_id, profiles_file);
  dds::sayOwnSharedMemoryPorts("swa_sim");
  if (scenario.vehicle.interface == sim::VehicleInterface::kPx4) {
    autopilot_ = std::make_unique<Px4Vehicles>(*participant_, n_, scenario.vehicle, scenario.imu.source);
  } else if (scenario.vehicle.interface == sim::VehicleInterface::kArdupilot) {
    autopilot_ = std::make_unique<ArdupilotVehicles>(*participant_, n_, scenario.vehicle, scenario.imu.source);
  }
  sensors_.attach(autopilot_.get());
}

void SimPorts::connect(int domain_id, const std::string& profiles_file) {
  participant_ = std::make_unique<dds::Participant>("swa_sim", domain_id, profiles_file);
  world_ports_.open(*participant_);
  const bool autopilot = scenario_.vehicle.interface != sim::VehicleInterface::kDirect;
  // With GNSS from the autopilot the bridges write swa/uav<i>/gnss; the simulator reports the fix as PX4 does.
  const bool own_gnss = !autopilot || scenario_.vehicle.gnss_source == sim::GnssSource::kSwa;
  // In the ros2 naming each sample keeps its own topic, where ROS tools expect them.
  sensors_.useFrames(frames_allowed_ && !autopilot && scenario_.agent.sensor.input == agent::DetectionInput::kSwa &&
                     participant_->wireNames().naming == dds::Naming::kSwa);
  for (int i = 0; i < n_; ++i) {
    sensors_.addUav(*participant_, i, autopilot, own_gnss);
    if (autopilot) continue;
    cmd_.push_back(participant_->readerWithOrigin<msg::VelocitySetpointPubSubType>(
        dds::topics::cmdVel(i), dds::qos::kCommandReader,
        [this, i](msg::VelocitySetpoint&& m, const dds::WriterGuid& w) {
          queue_.push(Answer{i, std::move(m), Clock::now(), w, true});
        }));
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
    sensors_.unmatched(i, missing);
    if (autopilot_) {
      autopilot_->unmatched(i, missing);
      continue;
    }
    if (cmd_[static_cast<std::size_t>(i)].matched() < 1) missing.push_back(dds::topics::cmdVel(i) + " (no writer)");
  }
  world_ports_.unmatched(missing);
  return missing;
}

void SimPorts::stepTaken(Clock::time_point t) {
  if (time_latency_) latency_.stepTaken(wallNs(t));
}

void SimPorts::publishStepOutputs(const AliveFn& alive) {
  if (world_.step_index() % 10 == 0) noteYoungerTwins();
  world_ports_.publishStepOutputs(alive);
}

std::vector<std::optional<agent::StampNs>> SimPorts::publishSensors(std::optional<Clock::time_point> due) {
  resend_after_reconnect_ = false;  // a new step: its samples go out on the new writers
  return sensors_.publish(due, time_latency_ ? &latency_ : nullptr);
}

void SimPorts::repeatWhileWaiting(const std::vector<int>& uavs) {
  if (autopilot_) {
    for (const int uav : uavs) autopilot_->repeatAttitude(uav);
    return;
  }
  if (!resend_after_reconnect_) return;
  resend_after_reconnect_ = false;
  for (const int uav : uavs) sensors_.resend(uav);
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

std::string SimPorts::commandTopic(int uav) const {
  return autopilot_ ? autopilot_->commandTopic(uav) : dds::topics::cmdVel(uav);
}

bool SimPorts::olderTwinRuns() {
  if (!participant_->mustGiveWay()) {
    noteYoungerTwins();
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

void SimPorts::noteYoungerTwins() {
  for (const dds::Peer& twin : participant_->takeYoungerTwins()) {
    std::fprintf(stderr,
                 "swa_sim: a second swa_sim (pid %ld on host %s) joined this swarm; it started later and must refuse "
                 "to run\n",
                 twin.card->pid, twin.card->host.c_str());
  }
}

}  // namespace swa::sim_node

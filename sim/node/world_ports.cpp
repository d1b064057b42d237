// WorldPorts (world_ports.h): what the simulator says of the world as a whole each step and at the end, kept apart
// from each UAV's samples (sensor_ports.cpp) and the participant's life (sim_ports.cpp).
#include "world_ports.h"

#include <iomanip>
#include <stdexcept>

#include <swa/msg/ClockPubSubTypes.h>
#include <swa/msg/ScenarioEventPubSubTypes.h>
#include <swa/msg/SwarmTruthPubSubTypes.h>

#include "swa/dds/qos_profiles.h"
#include "swa/dds/topics.h"
#include "swa/sim/timing.h"
#include "swa/wire/world.h"

namespace swa::sim_node {

WorldPorts::WorldPorts(const sim::Scenario& scenario, const SimOptions& options, const sim::World& world,
                       SimSummary& summary)
    : scenario_(scenario), options_(options), world_(world), summary_(summary) {
  if (!options_.truth_out.empty()) {
    truth_csv_.open(options_.truth_out);
    if (!truth_csv_) throw std::runtime_error("cannot write --truth-out " + options_.truth_out);
    truth_csv_ << "step,t_ns,uav,x_m,y_m,vx_mps,vy_mps,ax_mps2,ay_mps2,heading_rad,agent_alive,gnss_valid,failsafe\n";
    truth_csv_ << std::setprecision(17);
  }
}

void WorldPorts::open(dds::Participant& participant) {
  events_ = participant.writer<msg::ScenarioEventPubSubType>(dds::topics::kEvents, dds::qos::kEventWriter);
  truth_ = participant.writer<msg::SwarmTruthPubSubType>(dds::topics::kTruth, dds::qos::kTruthWriter);
  clock_ = participant.writer<msg::ClockPubSubType>(dds::topics::kClock, dds::qos::kClockWriter);
}

void WorldPorts::unmatched(std::vector<std::string>& missing) const {
  if (truth_.matched() < options_.wait_monitors) missing.push_back(std::string(dds::topics::kTruth) + " (monitor)");
  if (events_.matched() < options_.wait_monitors) missing.push_back(std::string(dds::topics::kEvents) + " (monitor)");
}

void WorldPorts::publishStepOutputs(const AliveFn& alive) {
  for (const sim::Event& e : world_.events()) publishEvent(sim::eventOf(e));
  if (world_.step_index() % options_.truth_every == 0 || world_.finished()) publishTruth(alive);
  publishClock();
}

void WorldPorts::publishClock() {
  const wire::ClockTick tick{static_cast<std::uint64_t>(world_.step_index()), world_.time_ns(),
                             sim::stepPeriodNs(scenario_.dynamics.rate_hz)};
  msg::Clock m = wire::toMsg(tick, ++clock_seq_);
  if (!clock_.write(m)) ++summary_.write_failures;
}

void WorldPorts::publishTruth(const AliveFn& alive) {
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

void WorldPorts::publishEvent(const char* kind, int uav, double value, const std::string& text) {
  publishEvent({static_cast<double>(world_.time_ns()) * 1e-9, kind, uav, -1, value, text});
}

void WorldPorts::publishEvent(const sim::EventRecord& event) {
  msg::ScenarioEvent m = wire::toMsg(event, ++event_seq_);
  if (!events_.write(m)) ++summary_.write_failures;
}

void WorldPorts::publishEndBeforeStart(const std::string& why) {
  publishEvent(sim::event_kind::kScenarioEnd, sim::kAllUavs, 0.0, why);
  events_.waitForAcknowledgments(1.0);
}

void WorldPorts::publishEnd(const AliveFn& alive, bool completed) {
  if (last_truth_step_ != world_.step_index()) publishTruth(alive);
  publishEvent(sim::event_kind::kScenarioEnd, sim::kAllUavs, 0.0, completed ? "completed" : "interrupted");
  // Give late readers of the last samples a moment; events are TRANSIENT_LOCAL anyway.
  events_.waitForAcknowledgments(2.0);
  truth_.waitForAcknowledgments(2.0);
  if (truth_csv_.is_open()) truth_csv_.flush();
}

}  // namespace swa::sim_node

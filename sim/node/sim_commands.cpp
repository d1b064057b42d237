// SimPorts' inbound side: the commands of every UAV's commander, in the order they arrived, refused when another
// writer owns the UAV (command_gate.h), and applied to the world or the UAV's autopilot.
#include "sim_ports.h"

#include <cstdio>

#include "swa/sim/timing.h"
#include "world_command.h"

namespace swa::sim_node {
namespace {

std::string guidText(const dds::WriterGuid& g) {
  char text[3 * 16 + 1] = {};
  for (std::size_t k = 0; k < g.size(); ++k) std::snprintf(text + 3 * k, 4, k + 1 < g.size() ? "%02x." : "%02x", g[k]);
  return text;
}

}  // namespace

const std::vector<SimPorts::Answer>& SimPorts::drain(Clock::duration wait) {
  healDeafness();  // first: a re-created participant must not have lost what this drain would take
  batch_.clear();
  admitted_.clear();
  for (const dds::PeerKey& gone : participant_->takePeersGone()) gate_.participantGone(gone);
  if (autopilot_) {
    autopilot_->drain(batch_, wait, world_.time_ns(), [this](const Answer& a) { return fromCommander(a, a.received); });
  } else {
    queue_.drain(batch_, wait);
  }
  for (Answer& a : batch_) {
    if (fromCommander(a, a.received)) {
      admit(std::move(a));
    } else {
      refused_[static_cast<std::size_t>(a.uav)] = std::move(a);
    }
  }
  // A command refused a moment ago whose writer may command now that every newer command was heard (the old owner's
  // participant has left, or it fell silent): applied now, and timed from now (command_gate.h).
  const Clock::time_point now = Clock::now();
  for (std::size_t k = 0; k < refused_.size(); ++k) {
    std::optional<Answer>& held = refused_[k];
    if (!held) continue;
    const dds::Held verdict = gate_.heldCommand(held->uav, held->writer, held->received, now);
    if (verdict == dds::Held::kRelease) {
      held->received = now;
      if (fromCommander(*held, now)) admit(std::move(*held));
    }
    if (verdict != dds::Held::kKeep) held.reset();
  }
  return admitted_;
}

void SimPorts::admit(Answer&& a) {
  if (a.setpoint.uav_id() != static_cast<std::uint32_t>(a.uav)) {
    ++summary_.ignored_commands;
    return;
  }
  if (time_latency_) {
    latency_.answered(a.uav, a.setpoint.answered_seq(), a.setpoint.answered_stamp_ns(), wallNs(a.received));
  }
  admitted_.push_back(std::move(a));
}

void SimPorts::apply(const Answer& a) {
  if (autopilot_) {
    autopilot_->apply(a);
  } else if (const std::optional<agent::VelocityCommand> command = worldCommand(a.setpoint)) {
    world_.command(a.uav, *command);
  } else {
    ++summary_.ignored_commands;  // a non-finite number: the previous setpoint stays in force
    return;
  }
  ++summary_.applied_commands;
}

bool SimPorts::fromCommander(const Answer& a, Clock::time_point at) {
  const dds::Admission admission = gate_.admit(a.uav, a.writer, at);
  if (admission == dds::Admission::kRefused) {
    ++summary_.refused_commands;
    if (gate_.firstRefusal(a.uav, a.writer)) {
      summary_.refused_writers = gate_.refusedWriters();
      std::fprintf(stderr,
                   "swa_sim: t = %.2f s: a second writer on %s (writer %s) while the current one is active: its "
                   "commands are refused (a second agent with this id, or another program writing it)\n",
                   sim::stampSeconds(world_.time_ns()), commandTopic(a.uav).c_str(), guidText(a.writer).c_str());
    }
    return false;
  }
  if (admission == dds::Admission::kHandover && gate_.handovers() != summary_.command_handovers) {
    summary_.command_handovers = gate_.handovers();
    std::fprintf(stderr, "swa_sim: t = %.2f s: %s now written by writer %s (the previous one fell silent or left)\n",
                 sim::stampSeconds(world_.time_ns()), commandTopic(a.uav).c_str(), guidText(a.writer).c_str());
  }
  return true;
}

}  // namespace swa::sim_node

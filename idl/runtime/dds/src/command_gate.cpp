#include "swa/dds/command_gate.h"

#include <algorithm>
#include <stdexcept>

namespace swa::dds {
namespace {
// Refused writers remembered for reporting once: beyond this many, further ones are still refused and counted, only
// not named (a flood of new writers must not grow memory).
constexpr std::size_t kMaxReported = 1024;
}  // namespace

CommandGate::CommandGate(int uav_count, Clock::duration handover)
    : handover_(handover), owners_(static_cast<std::size_t>(uav_count)) {
  if (uav_count < 0) throw std::invalid_argument("CommandGate: negative UAV count");
}

Admission CommandGate::admit(int uav, const WriterId& writer, Clock::time_point received) {
  if (uav < 0 || static_cast<std::size_t>(uav) >= owners_.size()) throw std::out_of_range("CommandGate: UAV");
  std::optional<Owner>& owner = owners_[static_cast<std::size_t>(uav)];
  if (owner && owner->writer == writer) {
    if (received > owner->last_heard) owner->last_heard = received;
    owner->gone = false;
    return Admission::kOwner;
  }
  if (!admits(uav, writer, received)) {
    ++refused_;
    return Admission::kRefused;
  }
  if (owner) ++handovers_;
  owner = Owner{writer, received};
  return Admission::kHandover;
}

bool CommandGate::admits(int uav, const WriterId& writer, Clock::time_point at) const {
  const std::optional<Owner>& owner = owners_.at(static_cast<std::size_t>(uav));
  return !owner || owner->writer == writer || owner->gone || at - owner->last_heard >= handover_;
}

Held CommandGate::heldCommand(int uav, const WriterId& writer, Clock::time_point received,
                              Clock::time_point now) const {
  if (now - received >= 2 * handover_) return Held::kDrop;  // too old to apply: the UAV has moved on
  return admits(uav, writer, now) ? Held::kRelease : Held::kKeep;
}

bool CommandGate::firstRefusal(int uav, const WriterId& writer) {
  if (reported_.size() >= kMaxReported) return false;
  return reported_.insert({uav, writer}).second;
}

void CommandGate::shift(Clock::duration lost, Clock::time_point now) {
  for (std::optional<Owner>& owner : owners_) {
    if (owner) owner->last_heard = std::min(owner->last_heard + lost, now);
  }
}

void CommandGate::participantGone(const std::array<std::uint8_t, 12>& prefix) {
  for (std::optional<Owner>& owner : owners_) {
    if (owner && std::equal(prefix.begin(), prefix.end(), owner->writer.begin())) owner->gone = true;
  }
}

}  // namespace swa::dds

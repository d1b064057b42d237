#pragma once
// The simulator's world topics <-> core types, both directions: swa/truth (SwarmTruth <-> sim::UavTruth per UAV
// plus whether its agent answers), swa/events (ScenarioEvent <-> sim::EventRecord) and swa/clock. The simulator
// node publishes toMsg(); the monitor and the tests read fromMsg().

#include <cstdint>
#include <optional>
#include <vector>

#include <swa/msg/Clock.h>
#include <swa/msg/ScenarioEvent.h>
#include <swa/msg/SwarmTruth.h>

#include "swa/sim/events.h"
#include "swa/sim/world.h"

namespace swa::wire {

// One swa/truth sample. The message carries id, position, velocity, acceleration, heading and GNSS validity of each
// UAV (not its failsafe flag or gust), and per UAV whether its agent answers (`agent_alive`, same order).
struct SwarmTruth {
  agent::StampNs stamp_ns = 0;
  std::vector<sim::UavTruth> uavs;
  std::vector<bool> agent_alive;
};

msg::SwarmTruth toMsg(const SwarmTruth& truth, std::uint32_t seq);
// Ids above INT_MAX are -1: no UAV has them, so they never alias one.
SwarmTruth fromMsg(const msg::SwarmTruth& m);

// The event's time (t_s) becomes the header stamp in nanoseconds, exactly for any run shorter than about 100 days.
// Throws std::invalid_argument for a kind that is not one of sim::event_kind (a programming error).
msg::ScenarioEvent toMsg(const sim::EventRecord& event, std::uint32_t seq);
// nullopt for a kind value this build does not know.
std::optional<sim::EventRecord> fromMsg(const msg::ScenarioEvent& m);

struct ClockTick {
  std::uint64_t step = 0;          // steps since the scenario started
  agent::StampNs sim_time_ns = 0;  // also the header stamp
  agent::StampNs step_period_ns = 0;
};

msg::Clock toMsg(const ClockTick& tick, std::uint32_t seq);
ClockTick fromMsg(const msg::Clock& m);

}  // namespace swa::wire

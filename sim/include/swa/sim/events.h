#pragma once
// The scenario events of a run as its record holds them (events.csv, summary.json): the world's events (GNSS lost
// and restored, collisions, failsafe), the simulator node's (agent dead / rejoined, scenario end). One spelling of
// each kind, whether the run was in-process (swa_batch) or over DDS (swa_monitor). Here, in the simulator's core,
// because the simulator raises them: the wire types (swa/wire/world.h) and the run record (swa/run_record) read this
// one spelling from below, and neither the simulator nor the wire reaches up into the monitor for it.

#include <string>

#include "swa/sim/world.h"

namespace swa::sim {

namespace event_kind {
inline constexpr const char* kGnssLost = "gnss_lost";
inline constexpr const char* kGnssRestored = "gnss_restored";
inline constexpr const char* kAgentDead = "agent_dead";
inline constexpr const char* kAgentRejoined = "agent_rejoined";
inline constexpr const char* kCollision = "collision";
inline constexpr const char* kFailsafe = "failsafe";
inline constexpr const char* kScenarioEnd = "scenario_end";
inline constexpr const char* kControlLost = "control_lost";          // a stand-in autopilot took the vehicle
inline constexpr const char* kControlRegained = "control_regained";  // and gave it back
}  // namespace event_kind

// uav / other_uav value of an event about every UAV (ScenarioEvent.idl ALL_UAVS) or about no second UAV.
constexpr int kAllUavs = -1;

struct EventRecord {
  double t_s = 0.0;  // sim time the event took effect
  std::string kind;  // one of event_kind
  int uav = kAllUavs;
  int other_uav = -1;
  double value = 0.0;
  std::string text;
};

// A world event as recorded (and as the simulator node publishes it).
EventRecord eventOf(const Event& e);

}  // namespace swa::sim

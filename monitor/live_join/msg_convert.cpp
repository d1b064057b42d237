#include "msg_convert.h"

#include "swa/agent/geometry.h"
#include "swa/wire/agent_state.h"
#include "swa/wire/world.h"

namespace swa::monitor_node {

TruthSample fromTruthMsg(const msg::SwarmTruth& m) {
  const wire::SwarmTruth w = wire::fromMsg(m);
  TruthSample t;
  t.stamp_ns = w.stamp_ns;
  t.uavs.reserve(w.uavs.size());
  for (const sim::UavTruth& u : w.uavs) t.uavs.push_back({u.id, u.position_m, u.velocity_mps, true});
  t.agent_alive = w.agent_alive;
  return t;
}

StateSample fromStateMsg(const msg::AgentState& m, const agent::FormationConfig& formation) {
  const wire::AgentStateSample w = wire::fromMsg(m);
  const agent::Diagnostics& d = w.diagnostics;
  StateSample s;
  s.uav = w.uav;
  s.stamp_ns = d.stamp_ns;
  s.mode = w.mode;
  s.estimate = monitor::estimateFromDiagnostics(d, formation);
  s.finite = agent::isFinite(d.position_m) && agent::isFinite(d.velocity_mps) && d.position_cov_m2.allFinite() &&
             d.velocity_cov_m2ps2.allFinite();
  if (!s.finite || !w.mode || !w.stage) s.estimate.valid = false;
  return s;
}

std::optional<EventRecord> fromEventMsg(const msg::ScenarioEvent& m) { return wire::fromMsg(m); }

}  // namespace swa::monitor_node

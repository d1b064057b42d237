#include "msg_convert.h"

#include <algorithm>
#include <cstdint>
#include <limits>

#include "swa/agent/diagnostics.h"
#include "swa/agent/geometry.h"

namespace swa::monitor_node {
namespace {

std::optional<agent::Mode> toMode(msg::AgentMode m) {
  switch (m) {
    case msg::MODE_SWA: return agent::Mode::kSwa;
    case msg::MODE_STANDALONE: return agent::Mode::kStandalone;
    case msg::MODE_ANCHORED: return agent::Mode::kAnchored;
  }
  return std::nullopt;  // an out-of-range value off the wire
}

std::optional<agent::Stage> toStage(msg::AgentStage s) {
  switch (s) {
    case msg::STAGE_INITIALIZING: return agent::Stage::kInitializing;
    case msg::STAGE_TRACKING: return agent::Stage::kTracking;
    case msg::STAGE_LOST: return agent::Stage::kLost;
    case msg::STAGE_NO_INPUT: return agent::Stage::kLost;  // not tracking: no estimate to score
  }
  return std::nullopt;
}

std::optional<const char*> kindName(msg::EventKind k) {
  switch (k) {
    case msg::EVENT_GNSS_LOST: return event_kind::kGnssLost;
    case msg::EVENT_GNSS_RESTORED: return event_kind::kGnssRestored;
    case msg::EVENT_AGENT_DEAD: return event_kind::kAgentDead;
    case msg::EVENT_AGENT_REJOINED: return event_kind::kAgentRejoined;
    case msg::EVENT_COLLISION: return event_kind::kCollision;
    case msg::EVENT_FAILSAFE: return event_kind::kFailsafe;
    case msg::EVENT_SCENARIO_END: return event_kind::kScenarioEnd;
  }
  return std::nullopt;
}

}  // namespace

TruthSample fromTruthMsg(const msg::SwarmTruth& m) {
  TruthSample t;
  t.stamp_ns = m.header().stamp_ns();
  t.uavs.reserve(m.uavs().size());
  t.agent_alive.reserve(m.uavs().size());
  for (const msg::UavTruth& u : m.uavs()) {
    monitor::UavTruth truth;
    // Ids above INT_MAX cannot be a UAV index; map them to -1 so they stay distinguishable and never alias one.
    truth.id = u.id() <= static_cast<std::uint32_t>(std::numeric_limits<int>::max()) ? static_cast<int>(u.id()) : -1;
    truth.position_m = agent::Vec2(u.x_m(), u.y_m());
    truth.velocity_mps = agent::Vec2(u.vx_mps(), u.vy_mps());
    truth.alive = true;
    t.uavs.push_back(truth);
    t.agent_alive.push_back(u.alive());
  }
  return t;
}

StateSample fromStateMsg(const msg::AgentState& m, const agent::FormationConfig& formation) {
  StateSample s;
  s.uav = m.uav_id() <= static_cast<std::uint32_t>(std::numeric_limits<int>::max()) ? static_cast<int>(m.uav_id()) : -1;
  s.stamp_ns = m.header().stamp_ns();
  s.mode = toMode(m.mode());
  const std::optional<agent::Stage> stage = toStage(m.stage());

  agent::Diagnostics d;
  d.stamp_ns = s.stamp_ns;
  d.mode = s.mode.value_or(agent::Mode::kStandalone);  // unknown: a mode that is never scored
  d.stage = stage.value_or(agent::Stage::kInitializing);
  d.position_m = agent::Vec2(m.est_x_m(), m.est_y_m());
  d.velocity_mps = agent::Vec2(m.est_vx_mps(), m.est_vy_mps());
  d.position_cov_m2 << m.pos_cov_xx_m2(), m.pos_cov_xy_m2(), m.pos_cov_xy_m2(), m.pos_cov_yy_m2();
  d.velocity_cov_m2ps2 << m.vel_cov_xx_m2ps2(), m.vel_cov_xy_m2ps2(), m.vel_cov_xy_m2ps2(), m.vel_cov_yy_m2ps2();
  d.frame_valid = m.frame_valid();
  d.frame_centre_m = agent::Vec2(m.frame_centre_x_m(), m.frame_centre_y_m());
  // More ids than the agent core can use (kMaxNeighbours) keep their count, so the record names an impossible
  // neighbour set and the NEES skips it as invalid instead of scoring a truncated frame.
  const std::size_t ids = m.neighbour_ids().size();
  d.neighbour_count = static_cast<int>(std::min<std::size_t>(ids, 1u << 20));
  std::copy_n(m.neighbour_ids().begin(), std::min<std::size_t>(ids, d.neighbour_ids.size()), d.neighbour_ids.begin());

  s.estimate = monitor::estimateFromDiagnostics(d, formation);
  s.finite = agent::isFinite(d.position_m) && agent::isFinite(d.velocity_mps) && d.position_cov_m2.allFinite() &&
             d.velocity_cov_m2ps2.allFinite();
  if (!s.finite || !s.mode || !stage) s.estimate.valid = false;
  return s;
}

std::optional<EventRecord> fromEventMsg(const msg::ScenarioEvent& m) {
  const std::optional<const char*> kind = kindName(m.kind());
  if (!kind) return std::nullopt;
  EventRecord e;
  e.t_s = stampSeconds(m.header().stamp_ns());
  e.kind = *kind;
  e.uav = m.uav_id();
  e.other_uav = m.other_uav_id();
  e.value = m.value();
  e.text = m.text();
  return e;
}

}  // namespace swa::monitor_node

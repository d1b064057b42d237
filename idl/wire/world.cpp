#include "swa/wire/world.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

#include "swa/wire/samples.h"

namespace swa::wire {
namespace {

namespace kind = sim::event_kind;

constexpr std::array<std::pair<msg::EventKind, const char*>, 9> kKinds{{
    {msg::EVENT_GNSS_LOST, kind::kGnssLost},
    {msg::EVENT_GNSS_RESTORED, kind::kGnssRestored},
    {msg::EVENT_AGENT_DEAD, kind::kAgentDead},
    {msg::EVENT_AGENT_REJOINED, kind::kAgentRejoined},
    {msg::EVENT_COLLISION, kind::kCollision},
    {msg::EVENT_FAILSAFE, kind::kFailsafe},
    {msg::EVENT_SCENARIO_END, kind::kScenarioEnd},
    {msg::EVENT_CONTROL_LOST, kind::kControlLost},
    {msg::EVENT_CONTROL_REGAINED, kind::kControlRegained},
}};

}  // namespace

msg::SwarmTruth toMsg(const SwarmTruth& truth, std::uint32_t seq) {
  msg::SwarmTruth m;
  m.header(header(truth.stamp_ns, seq));
  for (std::size_t k = 0; k < truth.uavs.size(); ++k) {
    const sim::UavTruth& t = truth.uavs[k];
    msg::UavTruth u;
    u.id(static_cast<std::uint32_t>(t.id));
    u.x_m(t.position_m.x());
    u.y_m(t.position_m.y());
    u.vx_mps(t.velocity_mps.x());
    u.vy_mps(t.velocity_mps.y());
    u.ax_mps2(t.acceleration_mps2.x());
    u.ay_mps2(t.acceleration_mps2.y());
    u.heading_rad(t.heading_rad);
    u.alive(k < truth.agent_alive.size() && truth.agent_alive[k]);
    u.gnss_valid(t.gnss_valid);
    m.uavs().push_back(u);
  }
  return m;
}

SwarmTruth fromMsg(const msg::SwarmTruth& m) {
  SwarmTruth t;
  t.stamp_ns = m.header().stamp_ns();
  t.uavs.reserve(m.uavs().size());
  t.agent_alive.reserve(m.uavs().size());
  for (const msg::UavTruth& u : m.uavs()) {
    sim::UavTruth s;
    s.id = u.id() <= static_cast<std::uint32_t>(std::numeric_limits<int>::max()) ? static_cast<int>(u.id()) : -1;
    s.position_m = agent::Vec2(u.x_m(), u.y_m());
    s.velocity_mps = agent::Vec2(u.vx_mps(), u.vy_mps());
    s.acceleration_mps2 = agent::Vec2(u.ax_mps2(), u.ay_mps2());
    s.heading_rad = u.heading_rad();
    s.gnss_valid = u.gnss_valid();
    t.uavs.push_back(s);
    t.agent_alive.push_back(u.alive());
  }
  return t;
}

msg::ScenarioEvent toMsg(const sim::EventRecord& event, std::uint32_t seq) {
  const auto it = std::find_if(kKinds.begin(), kKinds.end(), [&](const auto& k) { return event.kind == k.second; });
  if (it == kKinds.end()) throw std::invalid_argument("no ScenarioEvent kind for event '" + event.kind + "'");
  msg::ScenarioEvent m;
  m.header(header(std::llround(event.t_s * 1e9), seq));
  m.kind(it->first);
  m.uav_id(event.uav);
  m.other_uav_id(event.other_uav);
  m.value(event.value);
  m.text(event.text);
  return m;
}

std::optional<sim::EventRecord> fromMsg(const msg::ScenarioEvent& m) {
  const auto it = std::find_if(kKinds.begin(), kKinds.end(), [&](const auto& k) { return m.kind() == k.first; });
  if (it == kKinds.end()) return std::nullopt;
  sim::EventRecord e;
  e.t_s = static_cast<double>(m.header().stamp_ns()) * 1e-9;
  e.kind = it->second;
  e.uav = m.uav_id();
  e.other_uav = m.other_uav_id();
  e.value = m.value();
  e.text = m.text();
  return e;
}

msg::Clock toMsg(const ClockTick& tick, std::uint32_t seq) {
  msg::Clock m;
  m.header(header(tick.sim_time_ns, seq));
  m.step(tick.step);
  m.sim_time_ns(tick.sim_time_ns);
  m.step_period_ns(tick.step_period_ns);
  return m;
}

ClockTick fromMsg(const msg::Clock& m) { return {m.step(), m.sim_time_ns(), m.step_period_ns()}; }

}  // namespace swa::wire

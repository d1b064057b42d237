#include "swa/wire/agent_state.h"

#include <algorithm>
#include <limits>

namespace swa::wire {
namespace {

msg::AgentMode toMsg(agent::Mode m) {
  switch (m) {
    case agent::Mode::kSwa:
      return msg::MODE_SWA;
    case agent::Mode::kStandalone:
      return msg::MODE_STANDALONE;
    case agent::Mode::kAnchored:
      return msg::MODE_ANCHORED;
  }
  return msg::MODE_SWA;
}

msg::AgentStage toMsg(agent::Stage s) {
  switch (s) {
    case agent::Stage::kInitializing:
      return msg::STAGE_INITIALIZING;
    case agent::Stage::kTracking:
      return msg::STAGE_TRACKING;
    case agent::Stage::kLost:
      return msg::STAGE_LOST;
  }
  return msg::STAGE_INITIALIZING;
}

std::optional<agent::Mode> fromMsg(msg::AgentMode m) {
  switch (m) {
    case msg::MODE_SWA:
      return agent::Mode::kSwa;
    case msg::MODE_STANDALONE:
      return agent::Mode::kStandalone;
    case msg::MODE_ANCHORED:
      return agent::Mode::kAnchored;
  }
  return std::nullopt;  // an out-of-range value off the wire
}

std::optional<agent::Stage> fromMsg(msg::AgentStage s) {
  switch (s) {
    case msg::STAGE_INITIALIZING:
      return agent::Stage::kInitializing;
    case msg::STAGE_TRACKING:
      return agent::Stage::kTracking;
    case msg::STAGE_LOST:
      return agent::Stage::kLost;
    case msg::STAGE_NO_INPUT:
      return agent::Stage::kLost;  // not tracking: no estimate to score
  }
  return std::nullopt;
}

std::uint32_t count(int n) { return static_cast<std::uint32_t>(std::max(n, 0)); }

int checkedInt(std::uint64_t v) {
  return static_cast<int>(std::min<std::uint64_t>(v, static_cast<std::uint64_t>(std::numeric_limits<int>::max())));
}

}  // namespace

msg::AgentState toMsg(const agent::Diagnostics& d, std::uint32_t uav_id, std::uint32_t seq) {
  msg::AgentState m;
  m.header().stamp_ns(d.stamp_ns);
  m.header().seq(seq);
  m.uav_id(uav_id);
  m.mode(toMsg(d.mode));
  m.stage(toMsg(d.stage));
  m.est_x_m(d.position_m.x());
  m.est_y_m(d.position_m.y());
  m.est_vx_mps(d.velocity_mps.x());
  m.est_vy_mps(d.velocity_mps.y());
  m.pos_cov_xx_m2(d.position_cov_m2(0, 0));
  m.pos_cov_xy_m2(d.position_cov_m2(0, 1));
  m.pos_cov_yy_m2(d.position_cov_m2(1, 1));
  m.vel_cov_xx_m2ps2(d.velocity_cov_m2ps2(0, 0));
  m.vel_cov_xy_m2ps2(d.velocity_cov_m2ps2(0, 1));
  m.vel_cov_yy_m2ps2(d.velocity_cov_m2ps2(1, 1));
  m.frame_centre_x_m(d.frame_centre_m.x());
  m.frame_centre_y_m(d.frame_centre_m.y());
  m.frame_valid(d.frame_valid);
  const std::size_t n = std::min(
      {static_cast<std::size_t>(std::max(d.neighbour_count, 0)), d.neighbour_ids.size(), kMaxStateNeighbourIds});
  m.neighbour_ids().assign(d.neighbour_ids.begin(), d.neighbour_ids.begin() + static_cast<std::ptrdiff_t>(n));
  m.confirmed_tracks(count(d.confirmed_tracks));
  m.tentative_tracks(count(d.tentative_tracks));
  m.rejected_nonfinite(d.rejected.nonfinite);
  m.rejected_out_of_order(d.rejected.out_of_order);
  m.rejected_oversize(d.rejected.oversize);
  m.rejected_bad_id(d.rejected.bad_id);
  m.rejected_implausible(d.rejected.implausible);
  m.rejected_no_heading(d.rejected.no_heading);
  m.rejected_future_stamp(d.rejected.future);
  m.stamp_resyncs(d.stamp_resyncs);
  m.commands_sent(d.commands);
  m.gnss_valid(d.gnss_valid);
  return m;
}

AgentStateSample fromMsg(const msg::AgentState& m) {
  AgentStateSample s;
  s.uav = m.uav_id() <= static_cast<std::uint32_t>(std::numeric_limits<int>::max()) ? static_cast<int>(m.uav_id()) : -1;
  s.mode = fromMsg(m.mode());
  s.stage = fromMsg(m.stage());
  s.no_input = m.stage() == msg::STAGE_NO_INPUT;
  agent::Diagnostics& d = s.diagnostics;
  d.stamp_ns = m.header().stamp_ns();
  d.mode = s.mode.value_or(agent::Mode::kStandalone);
  d.stage = s.stage.value_or(agent::Stage::kInitializing);
  d.position_m = agent::Vec2(m.est_x_m(), m.est_y_m());
  d.velocity_mps = agent::Vec2(m.est_vx_mps(), m.est_vy_mps());
  d.position_cov_m2 << m.pos_cov_xx_m2(), m.pos_cov_xy_m2(), m.pos_cov_xy_m2(), m.pos_cov_yy_m2();
  d.velocity_cov_m2ps2 << m.vel_cov_xx_m2ps2(), m.vel_cov_xy_m2ps2(), m.vel_cov_xy_m2ps2(), m.vel_cov_yy_m2ps2();
  d.frame_valid = m.frame_valid();
  d.frame_centre_m = agent::Vec2(m.frame_centre_x_m(), m.frame_centre_y_m());
  const std::size_t ids = m.neighbour_ids().size();
  d.neighbour_count = static_cast<int>(std::min<std::size_t>(ids, 1u << 20));
  std::copy_n(m.neighbour_ids().begin(), std::min<std::size_t>(ids, d.neighbour_ids.size()), d.neighbour_ids.begin());
  d.confirmed_tracks = checkedInt(m.confirmed_tracks());
  d.tentative_tracks = checkedInt(m.tentative_tracks());
  d.rejected.nonfinite = m.rejected_nonfinite();
  d.rejected.out_of_order = m.rejected_out_of_order();
  d.rejected.oversize = m.rejected_oversize();
  d.rejected.bad_id = m.rejected_bad_id();
  d.rejected.implausible = m.rejected_implausible();
  d.rejected.no_heading = m.rejected_no_heading();
  d.rejected.future = m.rejected_future_stamp();
  d.stamp_resyncs = m.stamp_resyncs();
  d.commands = m.commands_sent();
  d.gnss_valid = m.gnss_valid();
  return s;
}

}  // namespace swa::wire

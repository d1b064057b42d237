#include "agent_state_msg.h"

#include <algorithm>

namespace swa::agent_node {
namespace {

msg::AgentMode toMsg(agent::Mode m) {
  switch (m) {
    case agent::Mode::kSwa: return msg::MODE_SWA;
    case agent::Mode::kStandalone: return msg::MODE_STANDALONE;
    case agent::Mode::kAnchored: return msg::MODE_ANCHORED;
  }
  return msg::MODE_SWA;
}

msg::AgentStage toMsg(agent::Stage s) {
  switch (s) {
    case agent::Stage::kInitializing: return msg::STAGE_INITIALIZING;
    case agent::Stage::kTracking: return msg::STAGE_TRACKING;
    case agent::Stage::kLost: return msg::STAGE_LOST;
  }
  return msg::STAGE_INITIALIZING;
}

std::uint32_t count(int n) { return static_cast<std::uint32_t>(std::max(n, 0)); }

}  // namespace

msg::AgentState toStateMsg(const agent::Diagnostics& d, std::uint32_t uav_id, std::uint32_t seq) {
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
  const std::size_t n = std::min({static_cast<std::size_t>(std::max(d.neighbour_count, 0)), d.neighbour_ids.size(),
                                  kMaxStateNeighbourIds});
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
  return m;
}

}  // namespace swa::agent_node

#include "status_line.h"

#include <cmath>

#include "swa/monitor/svg_plot.h"

namespace swa::monitor_node {
namespace {

std::string value(double v, int decimals) { return std::isfinite(v) ? monitor::formatFixed(v, decimals) : "n/a"; }

}  // namespace

std::string formatStatus(const LiveStatus& s) {
  if (!s.any_step) return "waiting for ground truth";
  return "t " + monitor::formatFixed(s.t_s, 1) + " s  d_NB " + value(s.d_nb_m, 2) + " m  min sep " +
         value(s.min_sep_m, 2) + " m  collisions " + std::to_string(s.collisions) + "  groups " +
         std::to_string(s.groups) + "  agents " + std::to_string(s.live_agents) + "/" + std::to_string(s.uavs) +
         " live";
}

bool StatusPacer::due(const LiveStatus& status, double wall_s) {
  if (tty_) {
    if (last_wall_s_ && wall_s - *last_wall_s_ < tty_period_s_) return false;
    last_wall_s_ = wall_s;
    return true;
  }
  if (!status.any_step) return false;
  const auto interval = static_cast<long long>(std::floor(status.t_s / log_period_s_));
  if (last_interval_ && interval <= *last_interval_) return false;
  last_interval_ = interval;
  return true;
}

}  // namespace swa::monitor_node

#include "swa/sim/gnss_model.h"

#include <algorithm>

#include "swa/sim/timing.h"

namespace swa::sim {

GnssModel::GnssModel(const GnssSetup& setup, int uav, Rng noise_rng)
    : dropout_start_s_(setup.dropout_start_s),
      dropout_end_s_(setup.dropout_end_s),
      std_m_(setup.std_m),
      kept_(std::find(setup.keep_uavs.begin(), setup.keep_uavs.end(), uav) != setup.keep_uavs.end()),
      noise_rng_(noise_rng) {
  for (const GnssWindow& w : setup.windows) {
    if (w.uav == uav) own_windows_s_.emplace_back(w.start_s, w.end_s);
  }
}

bool GnssModel::available(agent::StampNs stamp_ns) const {
  // Exact division: 10 s is exactly 1e10 ns / 1e9, so a window edge on a step falls on that step.
  const double t_s = stampSeconds(stamp_ns);
  const auto inside = [t_s](double start_s, double end_s) { return t_s >= start_s && t_s < end_s; };
  if (!kept_ && inside(dropout_start_s_, dropout_end_s_)) return false;
  return std::none_of(own_windows_s_.begin(), own_windows_s_.end(),
                      [&](const std::pair<double, double>& w) { return inside(w.first, w.second); });
}

agent::GnssSample GnssModel::sample(agent::StampNs stamp_ns, const agent::Vec2& true_position_m) {
  const double nx = noise_rng_.normal();
  const double ny = noise_rng_.normal();
  agent::GnssSample gnss;
  gnss.stamp_ns = stamp_ns;
  gnss.std_m = std_m_;
  gnss.valid = available(stamp_ns);
  if (gnss.valid) gnss.position_m = true_position_m + std_m_ * agent::Vec2(nx, ny);
  return gnss;
}

}  // namespace swa::sim

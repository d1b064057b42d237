#pragma once
// GNSS receiver of one UAV (DESIGN §4): truth + N(0, std^2) per axis while available; unavailable (valid = false)
// during the common dropout window [dropout_start_s, dropout_end_s) unless the UAV is in keep_uavs, and during
// each of the UAV's own windows [start_s, end_s) in GnssSetup::windows (whether or not it is in keep_uavs).

#include <utility>
#include <vector>

#include "swa/agent/geometry.h"
#include "swa/agent/samples.h"
#include "swa/sim/random.h"
#include "swa/sim/scenario.h"

namespace swa::sim {

class GnssModel {
 public:
  GnssModel(const GnssSetup& setup, int uav, Rng noise_rng);

  bool available(agent::StampNs stamp_ns) const;

  // The noise is drawn for every sample, valid or not, so a UAV's fixes do not depend on the dropout schedule.
  // An invalid sample carries a zero position and the configured std.
  agent::GnssSample sample(agent::StampNs stamp_ns, const agent::Vec2& true_position_m);

 private:
  double dropout_start_s_;
  double dropout_end_s_;
  std::vector<std::pair<double, double>> own_windows_s_;  // this UAV's [start, end) from GnssSetup::windows
  double std_m_;
  bool kept_;
  Rng noise_rng_;
};

}  // namespace swa::sim

#pragma once
// Mutual-perception sensor of one observer UAV (DESIGN §4): every other UAV within range and field of view (centred
// on body +x) is detected, unless missed, at its position relative to the observer in the observer's BODY frame.
//
// Noise models:
//  - isotropic: body position + N(0, noise_var I). Detection::covariance_m2 is left empty so the agent applies its
//    own configured R_o (the scenario's noise_var and the agent's R_o are separate knobs on purpose).
//  - range/bearing (LiDAR-like): range + N(0, range_std^2), bearing + N(0, bearing_std^2), and the covariance is
//    filled with the first-order propagation J diag(range_std^2, bearing_std^2) J^T evaluated at the MEASURED
//    range/bearing (all a real sensor knows). Range is floored at range_std and each std at 1 mm / 1 urad in that
//    covariance only, so it stays positive definite for a target at zero range or a noise-free configuration.
// Clutter: Poisson(clutter_rate) false positives per scan, uniform in area over the sensing disc sector. Clutter is
// ALWAYS anonymous (target_id = kAnonymousId), also when the sensor reports IDs: a spurious return has no identity,
// and a fabricated ID would collide with a real UAV's track in the agent.
// The order of detections within a scan is shuffled: a real sensor does not sort its returns by UAV, and with IDs
// off a fixed order would leak the identity the model is meant to hide.

#include <vector>

#include "swa/agent/geometry.h"
#include "swa/agent/samples.h"
#include "swa/sim/random.h"
#include "swa/sim/scenario.h"

namespace swa::sim {

struct MpsStreams {
  Rng miss, noise, clutter, order;
};

class MpsModel {
 public:
  MpsModel(const MpsSetup& setup, MpsStreams streams);

  // positions_m[j] is UAV j's true world position; the observer is skipped. observer_heading_rad is its true
  // heading. A scan with nothing detected still returns a set (the agent learns that a scan happened).
  agent::DetectionSet scan(agent::StampNs stamp_ns, int observer, const std::vector<agent::Vec2>& positions_m,
                           double observer_heading_rad);

  // Linearised covariance of a range/bearing measurement, body frame.
  static agent::Mat2 rangeBearingCovariance(double range_m, double bearing_rad, double range_std_m,
                                            double bearing_std_rad);

 private:
  bool inFieldOfView(double bearing_rad) const;
  agent::Detection measure(int target_id, const agent::Vec2& body_m);
  agent::Detection clutterReturn();

  MpsSetup setup_;
  double half_fov_rad_;
  double mount_rad_;
  bool all_round_;
  MpsStreams rng_;
};

}  // namespace swa::sim

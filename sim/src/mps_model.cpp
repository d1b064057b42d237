#include "swa/sim/mps_model.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace swa::sim {

namespace {
// Floors of the reported covariance only (the noise actually drawn uses the configured stds).
constexpr double kMinCovStd = 1e-3;      // m
constexpr double kMinBearingStd = 1e-6;  // rad
}  // namespace

MpsModel::MpsModel(const MpsSetup& setup, MpsStreams streams)
    : setup_(setup),
      half_fov_rad_(0.5 * setup.fov_deg * M_PI / 180.0),
      mount_rad_(setup.mount_deg * M_PI / 180.0),
      all_round_(setup.fov_deg >= 360.0),
      rng_(std::move(streams)) {}

bool MpsModel::inFieldOfView(double bearing_rad) const {
  return all_round_ || std::abs(std::remainder(bearing_rad - mount_rad_, 2.0 * M_PI)) <= half_fov_rad_;
}

agent::Mat2 MpsModel::rangeBearingCovariance(double range_m, double bearing_rad, double range_std_m,
                                             double bearing_std_rad) {
  const double range = std::max(std::abs(range_m), std::max(range_std_m, kMinCovStd));
  const double sr = std::max(range_std_m, kMinCovStd);
  const double sb = std::max(bearing_std_rad, kMinBearingStd);
  const double c = std::cos(bearing_rad);
  const double s = std::sin(bearing_rad);
  agent::Mat2 jacobian;
  jacobian << c, -range * s, s, range * c;
  const agent::Vec2 variances(sr * sr, sb * sb);
  agent::Mat2 cov = jacobian * variances.asDiagonal() * jacobian.transpose();
  cov(0, 1) = cov(1, 0) = 0.5 * (cov(0, 1) + cov(1, 0));  // exactly symmetric, as the agent checks
  return cov;
}

agent::Detection MpsModel::measure(int target_id, const agent::Vec2& body_m) {
  agent::Detection det;
  det.target_id = setup_.ids ? target_id : agent::kAnonymousId;
  if (setup_.noise_model == MpsNoiseModel::kIsotropic) {
    const double nx = rng_.noise.normal();
    const double ny = rng_.noise.normal();
    det.position_body_m = body_m + std::sqrt(setup_.noise_var_m2) * agent::Vec2(nx, ny);
  } else {
    const double nr = rng_.noise.normal();
    const double nb = rng_.noise.normal();
    const double range = body_m.norm() + setup_.range_std_m * nr;
    const double bearing = std::atan2(body_m.y(), body_m.x()) + setup_.bearing_std_rad * nb;
    det.position_body_m = range * agent::Vec2(std::cos(bearing), std::sin(bearing));
    det.covariance_m2 = rangeBearingCovariance(range, bearing, setup_.range_std_m, setup_.bearing_std_rad);
  }
  return det;
}

agent::Detection MpsModel::clutterReturn() {
  // Uniform in area: radius ~ R sqrt(u).
  const double u = rng_.clutter.uniform();
  const double bearing =
      all_round_ ? rng_.clutter.uniform(-M_PI, M_PI) : mount_rad_ + rng_.clutter.uniform(-half_fov_rad_, half_fov_rad_);
  const double range = setup_.range_m * std::sqrt(u);
  agent::Detection det;
  det.target_id = agent::kAnonymousId;
  det.position_body_m = range * agent::Vec2(std::cos(bearing), std::sin(bearing));
  if (setup_.noise_model == MpsNoiseModel::kRangeBearing) {
    det.covariance_m2 = rangeBearingCovariance(range, bearing, setup_.range_std_m, setup_.bearing_std_rad);
  }
  return det;
}

agent::DetectionSet MpsModel::scan(agent::StampNs stamp_ns, int observer, const std::vector<agent::Vec2>& positions_m,
                                   double observer_heading_rad) {
  agent::DetectionSet set;
  set.stamp_ns = stamp_ns;
  const auto self = static_cast<std::size_t>(observer);
  const agent::Mat2 to_body = agent::rotation(-observer_heading_rad);
  for (std::size_t j = 0; j < positions_m.size(); ++j) {
    if (j == self) continue;
    const agent::Vec2 relative = positions_m[j] - positions_m[self];
    if (relative.norm() > setup_.range_m) continue;
    const agent::Vec2 body = to_body * relative;
    if (!inFieldOfView(std::atan2(body.y(), body.x()))) continue;
    if (rng_.miss.uniform() < setup_.miss_probability) continue;
    set.detections.push_back(measure(static_cast<int>(j), body));
  }
  const int clutter = rng_.clutter.poisson(setup_.clutter_rate);
  for (int c = 0; c < clutter; ++c) set.detections.push_back(clutterReturn());
  // Fisher-Yates with the project's own index draw (std::shuffle's algorithm is library-specific).
  for (std::size_t i = set.detections.size(); i > 1; --i) {
    std::swap(set.detections[i - 1], set.detections[rng_.order.index(i)]);
  }
  return set;
}

}  // namespace swa::sim

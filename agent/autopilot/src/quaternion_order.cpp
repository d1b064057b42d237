#include "swa/autopilot/quaternion_order.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace swa::ardupilot {
namespace {

// R^T (0, 0, -1) for the rotation of q, q of any non-zero norm: minus R's last row.
SpecificForce downInBody(const px4::Quaternion& q) {
  const double n2 = q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z;
  return SpecificForce{-2.0 * (q.x * q.z - q.w * q.y) / n2, -2.0 * (q.y * q.z + q.w * q.x) / n2,
                       -(1.0 - 2.0 * (q.x * q.x + q.y * q.y) / n2)};
}

double norm(const SpecificForce& f) { return std::sqrt(f.x * f.x + f.y * f.y + f.z * f.z); }

}  // namespace

double gravityMismatchDeg(const px4::Quaternion& attitude, const SpecificForce& force) {
  const double n2 =
      attitude.w * attitude.w + attitude.x * attitude.x + attitude.y * attitude.y + attitude.z * attitude.z;
  const double f = norm(force);
  if (!std::isfinite(n2) || n2 <= 0.0 || !std::isfinite(f) || f <= 0.0) {
    return std::numeric_limits<double>::quiet_NaN();
  }
  const SpecificForce p = downInBody(attitude);
  const double c = (p.x * force.x + p.y * force.y + p.z * force.z) / (norm(p) * f);
  return std::acos(std::clamp(c, -1.0, 1.0)) * 180.0 / M_PI;
}

SpecificForce restingForceOf(const px4::Quaternion& attitude) {
  const SpecificForce d = downInBody(attitude);
  constexpr double g = QuaternionOrderFinder::kGravityMps2;
  return SpecificForce{g * d.x, g * d.y, g * d.z};
}

std::optional<QuaternionLayout> QuaternionOrderFinder::onSample(const OrientationFields& fields,
                                                                const SpecificForce& force, bool disarmed) {
  ++samples_;
  if (decided_) return decided_;
  if (!disarmed) return std::nullopt;
  if (!(std::abs(norm(force) - kGravityMps2) <= kStillToleranceMps2)) return std::nullopt;  // NaN too
  const double ros =
      gravityMismatchDeg(attitudeOf(fields.x, fields.y, fields.z, fields.w, QuaternionLayout::kRos), force);
  const double wxyz =
      gravityMismatchDeg(attitudeOf(fields.x, fields.y, fields.z, fields.w, QuaternionLayout::kWxyzInXyzw), force);
  std::optional<QuaternionLayout> vote;
  if (ros < kAgreeDeg && wxyz > kDisagreeDeg) vote = QuaternionLayout::kRos;
  if (wxyz < kAgreeDeg && ros > kDisagreeDeg) vote = QuaternionLayout::kWxyzInXyzw;
  if (!vote) return std::nullopt;  // a blind spot, or neither order agrees (not at rest after all)
  ++votes_;
  if (leading_ != vote) {
    if (leading_) ++reversals_;
    leading_ = vote;
    run_ = 0;
  }
  if (++run_ >= kVotesNeeded) decided_ = vote;
  return decided_;
}

}  // namespace swa::ardupilot

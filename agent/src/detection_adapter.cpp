#include "swa/agent/detection_adapter.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace swa::agent {
namespace {

// Off-diagonal terms that differ by more than this fraction of the diagonal are not a covariance's rounding.
constexpr double kSymmetryTolerance = 1e-6;
constexpr std::int64_t kMaxSec = 9'000'000'000LL;  // ~285 years: beyond it sec * 1e9 overflows StampNs

}  // namespace

std::optional<long long> numericId(const std::string& id) {
  if (id.empty() || id.size() > 9 || id.find_first_not_of("0123456789") != std::string::npos) return std::nullopt;
  return std::stoll(id);
}

std::vector<std::string> splitClasses(const std::string& list) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (start <= list.size()) {
    const std::size_t comma = std::min(list.find(',', start), list.size());
    if (comma > start) out.push_back(list.substr(start, comma - start));
    start = comma + 1;
  }
  return out;
}

std::optional<Mat2> DetectionAdapter::bodyCovariance(const std::array<double, 36>& c, double yaw_rad) {
  const double xx = c[0], xy = c[1], yx = c[6], yy = c[7];
  const bool finite = std::isfinite(xx) && std::isfinite(xy) && std::isfinite(yx) && std::isfinite(yy);
  const double scale = std::max(std::abs(xx), std::abs(yy));
  const bool symmetric = finite && std::abs(xy - yx) <= kSymmetryTolerance * scale;
  const double off = 0.5 * (xy + yx);
  // Both eigenvalues within [min, max]: a strongly correlated block can have a fine diagonal and still claim a
  // sub-millimetre accuracy across its main axis.
  const double mean = 0.5 * (xx + yy);
  const double spread = std::hypot(0.5 * (xx - yy), off);
  const double smallest = mean - spread, largest = mean + spread;
  const bool positive = symmetric && smallest >= config_.min_variance_m2 && largest <= config_.max_variance_m2;
  if (!positive) return std::nullopt;
  Mat2 s;
  s << xx, off, off, yy;
  const double cy = std::cos(yaw_rad), sy = std::sin(yaw_rad);
  Mat2 r;
  r << cy, -sy, sy, cy;
  Mat2 body = r * s * r.transpose();
  body = 0.5 * (body + body.transpose()).eval();
  return body;
}

std::optional<DetectionSet> DetectionAdapter::convert(const ForeignDetectionSet& in) {
  ++counters_.sets_in;
  const bool sensor_frame = !config_.sensor_frame_id.empty() && in.frame_id == config_.sensor_frame_id;
  if (!sensor_frame &&
      std::find(config_.frame_ids.begin(), config_.frame_ids.end(), in.frame_id) == config_.frame_ids.end()) {
    ++counters_.unknown_frame;
    return std::nullopt;
  }
  if (in.sec < 0 || in.sec > kMaxSec || in.nanosec >= 1'000'000'000u) {
    ++counters_.bad_stamp;
    return std::nullopt;
  }
  if (in.detections.size() > config_.max_detections) {
    ++counters_.oversize;
    return std::nullopt;
  }
  DetectionSet out;
  out.stamp_ns = in.sec * 1'000'000'000LL + static_cast<StampNs>(in.nanosec);
  out.detections.reserve(in.detections.size());
  // A body frame is the body; the sensor frame sits where the configuration says.
  const double yaw = sensor_frame ? config_.sensor_yaw_rad : 0.0;
  const Vec2 offset = sensor_frame ? config_.sensor_offset_m : Vec2::Zero();
  const double cy = std::cos(yaw), sy = std::sin(yaw);
  for (const ForeignDetection& d : in.detections) {
    if (!config_.classes.empty() && d.class_id &&
        std::find(config_.classes.begin(), config_.classes.end(), *d.class_id) == config_.classes.end()) {
      ++counters_.other_class;
      continue;
    }
    if (!std::isfinite(d.x_m) || !std::isfinite(d.y_m)) {
      ++counters_.nonfinite_position;
      continue;
    }
    Detection det;
    det.position_body_m = offset + Vec2(cy * d.x_m - sy * d.y_m, sy * d.x_m + cy * d.y_m);
    if (!det.position_body_m.allFinite()) {  // finite but near the largest double: the rotation overflowed
      ++counters_.nonfinite_position;
      continue;
    }
    const bool unknown = !d.covariance || ((*d.covariance)[0] == 0.0 && (*d.covariance)[1] == 0.0 &&
                                           (*d.covariance)[6] == 0.0 && (*d.covariance)[7] == 0.0);
    if (unknown) {
      ++counters_.covariance_missing;
    } else if (const std::optional<Mat2> c = bodyCovariance(*d.covariance, yaw)) {
      det.covariance_m2 = *c;
    } else {
      ++counters_.covariance_repaired;
    }
    if (d.id && *d.id >= 0 && *d.id <= std::numeric_limits<int>::max()) {
      det.target_id = static_cast<int>(*d.id);
    } else {
      ++counters_.anonymous;
    }
    out.detections.push_back(det);
  }
  ++counters_.sets_out;
  return out;
}

}  // namespace swa::agent

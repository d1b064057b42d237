#include "swa/px4/accelerometer.h"

#include <cmath>

namespace swa::px4 {
namespace {

// sensor_combined's RELATIVE_TIMESTAMP_INVALID (msg/SensorCombined.msg): the accelerometer values are invalid.
constexpr std::int32_t kRelativeTimestampInvalid = 2147483647;

}  // namespace

bool AccelerometerPairing::onSensorCombined(std::uint64_t timestamp_us, std::int32_t accelerometer_relative_us,
                                            const float (&accel)[3]) {
  ++received_;
  const bool finite = std::isfinite(accel[0]) && std::isfinite(accel[1]) && std::isfinite(accel[2]);
  const std::int64_t sample = static_cast<std::int64_t>(timestamp_us) + accelerometer_relative_us;
  if (accelerometer_relative_us == kRelativeTimestampInvalid || !finite || sample < 0 ||
      timestamp_us > static_cast<std::uint64_t>(INT64_MAX)) {
    ++invalid_;
    return false;
  }
  const auto sample_us = static_cast<std::uint64_t>(sample);
  if (newest_ && sample_us < newest_->sample_us) return true;  // an older reading arriving late changes nothing
  newest_ = AccelerometerReading{sample_us, accel[0], accel[1], accel[2]};
  return true;
}

std::optional<AccelerometerReading> AccelerometerPairing::pairWith(std::uint64_t attitude_sample_us) const {
  if (!newest_) return std::nullopt;
  const std::uint64_t skew = newest_->sample_us > attitude_sample_us ? newest_->sample_us - attitude_sample_us
                                                                     : attitude_sample_us - newest_->sample_us;
  if (skew > kMaxSkewUs) return std::nullopt;
  return newest_;
}

}  // namespace swa::px4

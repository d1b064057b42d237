#pragma once
// PX4 sends the accelerometer (sensor_combined) and the attitude (vehicle_attitude) on two topics; the agent needs
// both of one instant. The newest accelerometer sample goes with an attitude if it was taken within kMaxSkewUs of it,
// so that a vehicle whose sensor_combined stops (or is not on its topic list) gives tilt-only samples instead of
// pairing the attitude with a stale force. Pure: the link feeds it from the middleware's threads under its own lock.

#include <cstdint>
#include <optional>

namespace swa::px4 {

struct AccelerometerReading {
  std::uint64_t sample_us = 0;       // sensor_combined.timestamp + accelerometer_timestamp_relative
  double x = 0.0, y = 0.0, z = 0.0;  // FRD body, m/s^2
};

class AccelerometerPairing {
 public:
  // Two of PX4's IMU periods at its slowest default uXRCE-DDS rate of sensor_combined (100 Hz) less a margin: a
  // reading further away than this from the attitude belongs to another instant.
  static constexpr std::uint64_t kMaxSkewUs = 15'000;

  // A sensor_combined message; false (and ignored) if its accelerometer part is marked invalid or not finite.
  bool onSensorCombined(std::uint64_t timestamp_us, std::int32_t accelerometer_relative_us, const float (&accel)[3]);
  // The reading that goes with an attitude sampled at `attitude_sample_us`, if any.
  std::optional<AccelerometerReading> pairWith(std::uint64_t attitude_sample_us) const;

  std::uint64_t received() const { return received_; }
  std::uint64_t invalid() const { return invalid_; }

 private:
  std::optional<AccelerometerReading> newest_;
  std::uint64_t received_ = 0;
  std::uint64_t invalid_ = 0;
};

}  // namespace swa::px4

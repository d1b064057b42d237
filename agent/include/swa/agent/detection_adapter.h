#pragma once
// Relative detections from real detectors (issue #27), in one place: a ROS 2 vision_msgs/Detection3DArray or UVDAR's
// mrs_msgs/PoseWithCovarianceArrayStamped, read by the DDS adapter into a ForeignDetectionSet, become the agent's
// DetectionSet. Pure: no DDS.
//
// - Frame: the set's frame_id must be one the adapter can place: a body frame (x forward, y left, z up) named in
//   `frame_ids`, or the detector's own `sensor_frame_id`, placed on the body by its yaw and offset. Any other frame
//   drops the whole set (counted): a detection in a frame we cannot place would be a neighbour in the wrong place.
// - Class: with `classes` given, a detection whose class (vision_msgs: its best hypothesis's class_id; "" without
//   one) is not listed is dropped (counted): a clusterer's people and trees are no neighbours. UVDAR's carry no
//   class and are kept.
// - Time: the header's stamp (sec, nanosec) on the agent's clock; the agent rotates body to stable frame with the
//   IMU heading at that stamp, and rejects stamps in the future or out of order itself.
// - Noise: the x-y block of the 6x6 covariance, rotated into the body. An all-zero block means "unknown" (the ROS
//   convention): the configured measurement noise is used. A non-finite, non-symmetric or not positive-definite
//   block, or one far below any real detector's accuracy, is replaced by the configured noise too (counted as
//   repaired), never fed to a filter.
// - Ids: a UAV id when the message carries one (UVDAR's id; vision_msgs' string id when it is a decimal number),
//   anonymous otherwise. The agent itself drops ids above its limit and associates anonymous detections.
// - A detection with a non-finite position is dropped (counted); a set larger than `max_detections` is dropped.

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "swa/agent/samples.h"

namespace swa::agent {

struct ForeignDetection {
  double x_m = 0.0, y_m = 0.0, z_m = 0.0;            // in the set's frame
  std::optional<std::array<double, 36>> covariance;  // row-major 6x6 (x, y, z, three rotations); zeros: unknown
  std::optional<long long> id;
  std::optional<std::string> class_id;  // vision_msgs: the best hypothesis's ("" without one); UVDAR: none
};

struct ForeignDetectionSet {
  std::int64_t sec = 0;
  std::uint32_t nanosec = 0;
  std::string frame_id;
  std::vector<ForeignDetection> detections;
};

struct DetectionAdapterConfig {
  std::vector<std::string> frame_ids;   // body frames accepted (x forward, y left)
  std::string sensor_frame_id;          // the detector's own frame ("" = none), placed on the body by:
  double sensor_yaw_rad = 0.0;          // its x axis in the body, counter-clockwise
  Vec2 sensor_offset_m = Vec2::Zero();  // its origin in the body
  std::vector<std::string> classes;     // class ids taken for UAVs; empty: every detection
  std::size_t max_detections = 64;
  double min_variance_m2 = 1e-6;  // below this a covariance is not a measurement's (a placeholder)
  double max_variance_m2 = 1e4;
};

struct DetectionAdapterCounters {
  std::uint64_t sets_in = 0, sets_out = 0;
  std::uint64_t unknown_frame = 0, bad_stamp = 0, oversize = 0;   // whole sets dropped
  std::uint64_t nonfinite_position = 0, other_class = 0;          // detections dropped
  std::uint64_t covariance_repaired = 0, covariance_missing = 0;  // the configured noise used instead
  std::uint64_t anonymous = 0;
};

class DetectionAdapter {
 public:
  explicit DetectionAdapter(DetectionAdapterConfig config) : config_(std::move(config)) {}

  std::optional<DetectionSet> convert(const ForeignDetectionSet& in);
  const DetectionAdapterCounters& counters() const { return counters_; }

 private:
  std::optional<Mat2> bodyCovariance(const std::array<double, 36>& c, double yaw_rad);

  DetectionAdapterConfig config_;
  DetectionAdapterCounters counters_;
};

// A vision_msgs Detection3D's string id as a UAV id: a decimal number, else anonymous.
std::optional<long long> numericId(const std::string& id);
// "uav,drone" -> {"uav", "drone"}; empty items dropped.
std::vector<std::string> splitClasses(const std::string& list);

}  // namespace swa::agent

#pragma once
// Relative detections as real detectors publish them (agent.sensor.input): vision_msgs/Detection3DArray and UVDAR's
// mrs_msgs/PoseWithCovarianceArrayStamped, read into the agent's ForeignDetectionSet (detection_adapter.h converts
// it) and, for the simulator, written from a DetectionSet in the body frame "uav<I>/fcu".

#include <cstdint>
#include <string>

#include <swa/ros/Detection3DArray.h>
#include <swa/ros/PoseWithCovarianceArrayStamped.h>

#include "swa/agent/detection_adapter.h"
#include "swa/agent/samples.h"

namespace swa::wire {

// The id SWA's stand-in gives an anonymous UVDAR pose (upstream's id is a uint64; any id beyond the agent's limit reads
// as anonymous, this one as well).
constexpr std::uint64_t kUvdarNoId = 0xFFFFFFFFFFFFFFFFull;

// The body frame SWA's simulator names UAV `uav_id`'s detections in (x forward, y left, z up).
std::string bodyFrameId(std::uint32_t uav_id);

// Each Detection3D's position is that of its most likely hypothesis (results, highest score) with that hypothesis'
// covariance, or the bounding box centre without one when there is no hypothesis; its id a decimal `id`.
agent::ForeignDetectionSet foreignOf(const vision_msgs::msg::Detection3DArray& m);
agent::ForeignDetectionSet foreignOf(const mrs_msgs::msg::PoseWithCovarianceArrayStamped& m);

// The simulator's detections in either message: covariance the detection's (x-y block; zeros = unknown when it has
// none), ids when identified (vision_msgs: the decimal string, empty when anonymous; UVDAR: the id, kUvdarNoId when
// anonymous, which the adapter reads as anonymous: beyond any UAV id).
vision_msgs::msg::Detection3DArray detection3DArray(const agent::DetectionSet& s, std::uint32_t uav_id);
mrs_msgs::msg::PoseWithCovarianceArrayStamped poseArray(const agent::DetectionSet& s, std::uint32_t uav_id);

}  // namespace swa::wire

#include "swa/wire/ros_detections.h"

#include <limits>

#include "swa/wire/ros_types.h"

namespace swa::wire {
namespace {

std::array<double, 36> covarianceOf(const std::optional<agent::Mat2>& c) {
  std::array<double, 36> out{};
  if (c) {
    out[0] = (*c)(0, 0);
    out[1] = (*c)(0, 1);
    out[6] = (*c)(1, 0);
    out[7] = (*c)(1, 1);
  }
  return out;
}

std_msgs::msg::Header headerOf(const agent::DetectionSet& s, std::uint32_t uav_id) {
  std_msgs::msg::Header h;
  h.stamp(rosTime(s.stamp_ns));
  h.frame_id(bodyFrameId(uav_id));
  return h;
}

// A detection's pose: its body position, no rotation (the detector does not measure the neighbour's attitude).
geometry_msgs::msg::Pose poseOf(const agent::Detection& d) {
  geometry_msgs::msg::Pose p;
  p.position().x(d.position_body_m.x());
  p.position().y(d.position_body_m.y());
  p.orientation().w(1.0);
  return p;
}

agent::ForeignDetection foreignAt(const geometry_msgs::msg::Point& p) {
  agent::ForeignDetection f;
  f.x_m = p.x();
  f.y_m = p.y();
  f.z_m = p.z();
  return f;
}

void stampOf(const std_msgs::msg::Header& h, agent::ForeignDetectionSet& out) {
  out.sec = h.stamp().sec();
  out.nanosec = h.stamp().nanosec();
  out.frame_id = h.frame_id();
}

}  // namespace

std::string bodyFrameId(std::uint32_t uav_id) { return "uav" + std::to_string(uav_id) + "/fcu"; }

agent::ForeignDetectionSet foreignOf(const vision_msgs::msg::Detection3DArray& m) {
  agent::ForeignDetectionSet out;
  stampOf(m.header(), out);
  out.detections.reserve(m.detections().size());
  for (const vision_msgs::msg::Detection3D& d : m.detections()) {
    const vision_msgs::msg::ObjectHypothesisWithPose* best = nullptr;
    for (const auto& h : d.results()) {
      if (best == nullptr || h.hypothesis().score() > best->hypothesis().score()) best = &h;
    }
    agent::ForeignDetection f =
        foreignAt(best != nullptr ? best->pose().pose().position() : d.bbox().center().position());
    if (best != nullptr) f.covariance = best->pose().covariance();
    f.class_id = best != nullptr ? best->hypothesis().class_id() : std::string();
    f.id = agent::numericId(d.id());
    out.detections.push_back(f);
  }
  return out;
}

agent::ForeignDetectionSet foreignOf(const mrs_msgs::msg::PoseWithCovarianceArrayStamped& m) {
  agent::ForeignDetectionSet out;
  stampOf(m.header(), out);
  out.detections.reserve(m.poses().size());
  for (const mrs_msgs::msg::PoseWithCovarianceIdentified& p : m.poses()) {
    agent::ForeignDetection f = foreignAt(p.pose().position());
    f.covariance = p.covariance();
    // An id beyond long long (the sentinel among them) is no UAV's: anonymous, not a wrapped negative number.
    if (p.id() <= static_cast<std::uint64_t>(std::numeric_limits<long long>::max())) {
      f.id = static_cast<long long>(p.id());
    }
    out.detections.push_back(f);
  }
  return out;
}

vision_msgs::msg::Detection3DArray detection3DArray(const agent::DetectionSet& s, std::uint32_t uav_id) {
  vision_msgs::msg::Detection3DArray m;
  m.header(headerOf(s, uav_id));
  for (const agent::Detection& d : s.detections) {
    vision_msgs::msg::Detection3D out;
    out.header(m.header());
    vision_msgs::msg::ObjectHypothesisWithPose h;
    h.hypothesis().class_id("uav");
    h.hypothesis().score(1.0);
    h.pose().pose(poseOf(d));
    h.pose().covariance(covarianceOf(d.covariance_m2));
    out.results().push_back(h);
    out.bbox().center(h.pose().pose());
    if (d.target_id != agent::kAnonymousId) out.id(std::to_string(d.target_id));
    m.detections().push_back(out);
  }
  return m;
}

mrs_msgs::msg::PoseWithCovarianceArrayStamped poseArray(const agent::DetectionSet& s, std::uint32_t uav_id) {
  mrs_msgs::msg::PoseWithCovarianceArrayStamped m;
  m.header(headerOf(s, uav_id));
  for (const agent::Detection& d : s.detections) {
    mrs_msgs::msg::PoseWithCovarianceIdentified p;
    p.id(d.target_id == agent::kAnonymousId ? kUvdarNoId : static_cast<std::uint64_t>(d.target_id));
    p.pose(poseOf(d));
    p.covariance(covarianceOf(d.covariance_m2));
    m.poses().push_back(p);
  }
  return m;
}

}  // namespace swa::wire

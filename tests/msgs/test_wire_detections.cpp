// Real detectors' messages <-> the agent's detections (swa/wire/ros_detections.h): UVDAR's ids are 64 bits wide
// (mrs_msgs' uint64 id), and the ids no UAV can have read as anonymous rather than wrapping to a negative number.

#include <gtest/gtest.h>

#include <cstdint>

#include "swa/wire/ros_detections.h"

namespace swa::wire {
namespace {

mrs_msgs::msg::PoseWithCovarianceIdentified identified(std::uint64_t id) {
  mrs_msgs::msg::PoseWithCovarianceIdentified p;
  p.id(id);
  p.pose().position().x(4.0);
  return p;
}

TEST(WireDetections, UvdarIdsReadOverTheirWholeWidthAndTheImpossibleOnesAsAnonymous) {
  // GIVEN UVDAR poses with a small id, an id beyond 32 bits, the largest signed 64-bit one, one beyond it, and the
  // stand-in's no-id sentinel
  mrs_msgs::msg::PoseWithCovarianceArrayStamped m;
  for (const std::uint64_t id : {std::uint64_t{5}, std::uint64_t{1} << 33, std::uint64_t{0x7FFFFFFFFFFFFFFF},
                                 std::uint64_t{0x8000000000000000}, kUvdarNoId}) {
    m.poses().push_back(identified(id));
  }
  // WHEN the adapter's input is made of them
  const agent::ForeignDetectionSet f = foreignOf(m);
  // THEN the ids that fit keep their value (the agent drops those above its own limit), the others have none
  ASSERT_EQ(f.detections.size(), 5u);
  EXPECT_EQ(f.detections[0].id, 5);
  EXPECT_EQ(f.detections[1].id, 1LL << 33);
  EXPECT_EQ(f.detections[2].id, 0x7FFFFFFFFFFFFFFFLL);
  EXPECT_FALSE(f.detections[3].id);
  EXPECT_FALSE(f.detections[4].id);
  EXPECT_EQ(f.detections[4].x_m, 4.0);
}

TEST(WireDetections, TheStandInWritesTheSentinelForAnAnonymousDetectionAndTheIdOtherwise) {
  // GIVEN a detection of UAV 6 and an anonymous one
  agent::DetectionSet s;
  s.detections.resize(2);
  s.detections[0].target_id = 6;
  s.detections[1].target_id = agent::kAnonymousId;
  // WHEN UAV 2's simulator writes them as UVDAR does
  const mrs_msgs::msg::PoseWithCovarianceArrayStamped m = poseArray(s, 2);
  // THEN the identified one carries its id, the anonymous one the no-id sentinel, and both read back as they were
  ASSERT_EQ(m.poses().size(), 2u);
  EXPECT_EQ(m.poses()[0].id(), 6u);
  EXPECT_EQ(m.poses()[1].id(), kUvdarNoId);
  const agent::ForeignDetectionSet back = foreignOf(m);
  EXPECT_EQ(back.detections[0].id, 6);
  EXPECT_FALSE(back.detections[1].id);
  EXPECT_EQ(back.frame_id, "uav2/fcu");
}

}  // namespace
}  // namespace swa::wire

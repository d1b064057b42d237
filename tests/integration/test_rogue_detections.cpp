// Bad detector output through the detection adapters (issue #27), label fuzz: one swa_agent reads its detections as a
// real detector's message (sensor.input = vision_msgs or uvdar), a rogue publisher with a ROS 2 node's default QoS
// (profile ros2_default_writer: it must match) sends it IMU samples at 100 Hz and, every 10th step, a detection set:
// genuine ones, and ones with NaN and infinite positions, zero, NaN, asymmetric and negative covariances, frames it
// cannot place, a huge array, bad stamps. The agent stays alive, every command it
// sends is finite and within its speed limit, and it says at exit what it dropped and repaired.

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <thread>

#include <swa/msg/ImuPubSubTypes.h>
#include <swa/msg/VelocitySetpointPubSubTypes.h>
#include <swa/ros/Detection3DArrayPubSubTypes.h>
#include <swa/ros/PoseWithCovarianceArrayStampedPubSubTypes.h>

#include "resting_imu.h"
#include "rogue_agent_test.h"
#include "swa/dds/qos_profiles.h"
#include "swa/dds/sample_queue.h"
#include "swa/wire/ros_detections.h"
#include "swa/wire/ros_types.h"

namespace swa::testing {
namespace {

constexpr int kUav = 2;
constexpr agent::StampNs kMs = 1'000'000;
constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
constexpr double kVMax = 2.0;  // the agent's default control.v_max_mps

// One step's detection set, in the agent's body frame: genuine (three neighbours on a ring) or one kind of bad.
agent::DetectionSet detections(agent::StampNs t, int kind, std::mt19937_64& rng) {
  agent::DetectionSet s;
  s.stamp_ns = t;
  for (int j = 0; j < 3; ++j) {
    agent::Detection d;
    d.target_id = ringNeighbourId(j);
    d.position_body_m = ringNeighbour(j);
    agent::Mat2 c;
    c << 0.04, 0.0, 0.0, 0.04;
    d.covariance_m2 = c;
    s.detections.push_back(d);
  }
  std::uniform_real_distribution<double> big(-1e6, 1e6);
  switch (kind) {
    case 1:
      s.detections[0].position_body_m.x() = kNan;
      break;
    case 2:
      s.detections[1].position_body_m.y() = INFINITY;
      break;
    case 3:
      (*s.detections[0].covariance_m2)(0, 1) = 5.0;
      break;  // asymmetric after the writer's copy below
    case 4:
      *s.detections[2].covariance_m2 *= -1.0;
      break;
    case 5:
      (*s.detections[1].covariance_m2)(1, 1) = kNan;
      break;
    case 6:
      s.detections.resize(300, s.detections[0]);
      break;  // beyond limits.max_detections
    case 7:
      s.detections[0].position_body_m = agent::Vec2(big(rng), big(rng));
      break;
    default:
      break;
  }
  return s;
}

class RogueDetections : public RogueAgentTest, public ::testing::WithParamInterface<std::string> {
 protected:
  void SetUp() override {
    startAgentAndRogue("swa_rogue_detections", /*dir_per_test=*/true, 41, kUav,
                       "sensor:\n  input: " + GetParam() + "\n");
    if (GetParam() == "vision_msgs") {
      vision_ = rogue_->writer<vision_msgs::msg::Detection3DArrayPubSubType>(dds::topics::visionDetections(kUav),
                                                                             dds::qos::kRos2DefaultWriter);
    } else {
      uvdar_ = rogue_->writer<mrs_msgs::msg::PoseWithCovarianceArrayStampedPubSubType>(dds::topics::uvdarPoses(kUav),
                                                                                       dds::qos::kRos2DefaultWriter);
    }
  }

  int detectionsMatched() const { return vision_ ? vision_.matched() : uvdar_.matched(); }

  // The set as the detector would send it; `frame` replaces the body frame, the covariance's (0, 1) term is kept
  // and its (1, 0) term written as the symmetric value (so case 3 reaches the wire asymmetric).
  void send(const agent::DetectionSet& s, const std::string& frame) {
    if (vision_) {
      vision_msgs::msg::Detection3DArray m = wire::detection3DArray(s, kUav);
      m.header().frame_id(frame);
      vision_.write(m);
    } else {
      mrs_msgs::msg::PoseWithCovarianceArrayStamped m = wire::poseArray(s, kUav);
      m.header().frame_id(frame);
      uvdar_.write(m);
    }
  }

  dds::Writer<vision_msgs::msg::Detection3DArray> vision_;
  dds::Writer<mrs_msgs::msg::PoseWithCovarianceArrayStamped> uvdar_;
};

TEST_P(RogueDetections, BadDetectorOutputGivesNoBadCommand) {
  ASSERT_TRUE(waitFor([this] { return imu_.matched() > 0 && detectionsMatched() > 0; }, 20.0))
      << readFile(dir_ / "agent.log");
  // GIVEN 4 s of IMU at 100 Hz and a detection set every 10th step: kinds 0 (genuine) to 7 in turn, every third
  // set in a frame the agent cannot place, every fifth stamped 10 s ahead or before the epoch
  std::mt19937_64 rng(41);
  const std::string body = wire::bodyFrameId(kUav);
  std::uint32_t seq = 0;
  const auto start = SteadyClock::now();
  for (int i = 0; i < 400; ++i) {
    const agent::StampNs t = 1'000 * kMs + i * 10 * kMs;
    msg::Imu m = restingImu(kUav, t, ++seq);
    imu_.write(m);
    if (i % 10 == 0) {
      const int k = i / 10;
      agent::DetectionSet s = detections(t, k % 8, rng);
      if (k % 5 == 4) s.stamp_ns = k % 2 == 0 ? t + 10'000 * kMs : -5 * kMs;
      send(s, k % 3 == 2 ? std::string("uav2/uvdar_camera_left") : body);
    }
    std::this_thread::sleep_until(start + std::chrono::milliseconds(10 * (i + 1)));
  }
  ASSERT_TRUE(waitFor([this] { return cmds_.take(), cmds_.seen.size() >= 300; }, 10.0))
      << cmds_.seen.size() << " commands\n"
      << readFile(dir_ / "agent.log");
  // THEN the agent answered, every command finite and within the limit
  int bad = 0;
  for (const msg::VelocitySetpoint& c : cmds_.seen) {
    const double speed = std::hypot(c.vx_mps(), c.vy_mps());
    if (!std::isfinite(speed) || speed > kVMax + 1e-9 || !std::isfinite(c.yaw_rate_radps())) ++bad;
  }
  EXPECT_EQ(bad, 0);
  EXPECT_FALSE(agent_->wait(0.0)) << "the agent exited\n" << readFile(dir_ / "agent.log");
  // AND at exit (SIGTERM: status 0) it says what the adapter dropped and repaired
  EXPECT_EQ(agent_->stop(), 0);
  const std::string log = readFile(dir_ / "agent.log");
  const std::string line = log.substr(std::min(log.size(), log.find(GetParam() + " detections:")));
  std::cout << cmds_.seen.size() << " commands; " << line.substr(0, line.find('\n')) << "\n";
  EXPECT_NE(line.find("set(s) in"), std::string::npos) << log;
  EXPECT_EQ(line.find("dropped 0 in a frame"), std::string::npos) << line;
  EXPECT_EQ(line.find(" 0 detection(s) with a non-finite position"), std::string::npos) << line;
  EXPECT_EQ(line.find("covariance repaired 0,"), std::string::npos) << line;
}

INSTANTIATE_TEST_SUITE_P(Inputs, RogueDetections, ::testing::Values("vision_msgs", "uvdar"));

}  // namespace
}  // namespace swa::testing

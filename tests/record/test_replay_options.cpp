// swa_replay's command line and how it names a recording's topics (deploy/programs/replay).

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <vector>

#include "error_text.h"
#include "recorded_run.h"
#include "replay_options.h"

namespace swa::replay {
namespace {

std::string problemsOf(const std::vector<std::string>& args) {
  return testing::invalidArgumentText([&] { parseReplayOptions(args); });
}

TEST(ReplayOptions, FileFirstThenOptionsWithSafeDefaults) {
  const ReplayOptions o = parseReplayOptions({"run.mcap", "--uav", "3"});
  EXPECT_EQ(o.file, "run.mcap");
  ASSERT_TRUE(o.uav);
  EXPECT_EQ(*o.uav, 3);
  EXPECT_EQ(o.speed, 1.0);
  EXPECT_FALSE(o.lockstep);
  EXPECT_FALSE(o.check);
  EXPECT_TRUE(parseReplayOptions({"--help"}).help) << "--help needs no file";
}

TEST(ReplayOptions, EveryProblemAtOnce) {
  const std::string p = problemsOf({"--check", "--speed", "2", "--uav", "x", "--lockstep"});
  EXPECT_NE(p.find("FILE.mcap (first argument) is missing"), std::string::npos) << p;
  EXPECT_NE(p.find("--speed replays on DDS: not with --check"), std::string::npos) << p;
  EXPECT_NE(p.find("--lockstep replays on DDS"), std::string::npos) << p;
  EXPECT_NE(p.find("--uav 'x' is not a UAV index"), std::string::npos) << p;
  EXPECT_NE(problemsOf({"r.mcap", "--set", "agent.k=2"}).find("--set applies to --check"), std::string::npos);
  EXPECT_NE(problemsOf({"r.mcap", "--speed", "0"}).find("--speed 0 needs --lockstep"), std::string::npos);
  EXPECT_NE(problemsOf({"r.mcap", "--speed", "-1"}).find("--speed"), std::string::npos);
  EXPECT_EQ(problemsOf({"r.mcap", "--speed", "0", "--lockstep"}), "");
}

TEST(RecordedTopics, SwaTopicsUnderAnyRosNamespaceAndTheirUav) {
  EXPECT_EQ(swaTopicOf("/swa/uav3/imu"), "swa/uav3/imu");
  EXPECT_EQ(swaTopicOf("/team_a/swa/uav3/imu"), "swa/uav3/imu");
  EXPECT_EQ(swaTopicOf("/swa/truth"), "swa/truth");
  EXPECT_FALSE(swaTopicOf("/fmu/out/vehicle_status"));
  EXPECT_EQ(uavTopic("swa/uav12/cmd_vel"), std::make_pair(12, std::string("cmd_vel")));
  EXPECT_FALSE(uavTopic("swa/truth"));
  EXPECT_FALSE(uavTopic("swa/uavx/imu"));
  EXPECT_FALSE(uavTopic("swa/uav/imu"));
  EXPECT_FALSE(uavTopic("swa/uav99999999/imu")) << "an index too long to be one";
}

}  // namespace
}  // namespace swa::replay

// swa_mission's command line (issue #45): legs in the order given, a hold, and every bad line refused at once with
// what is wrong, before anything is sent.

#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "mission_options.h"

namespace swa::mission_tool {
namespace {

std::string problemsOf(const std::vector<std::string>& args) {
  try {
    parseMissionOptions(args);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(MissionOptions, LegsAreKeptInTheOrderGiven) {
  const MissionOptions o = parseMissionOptions({"--leg", "vel:0,2,30", "--leg=to:-5.5,0,4", "--expect", "8"});
  ASSERT_EQ(o.command.legs.size(), 2u);
  EXPECT_FALSE(o.command.hold);
  EXPECT_EQ(o.command.legs[0].kind, agent::MissionCommandLeg::Kind::kVelocity);
  EXPECT_EQ(o.command.legs[0].value, agent::Vec2(0, 2));
  EXPECT_EQ(o.command.legs[0].duration_s, 30.0);
  EXPECT_EQ(o.command.legs[1].kind, agent::MissionCommandLeg::Kind::kTo);
  EXPECT_EQ(o.command.legs[1].value, agent::Vec2(-5.5, 0));
  EXPECT_EQ(o.command.legs[1].speed_mps, 4.0);
  EXPECT_EQ(o.expect, 8);
}

TEST(MissionOptions, AHoldHasNoLegs) {
  const MissionOptions o = parseMissionOptions({"--hold"});
  EXPECT_TRUE(o.command.hold);
  EXPECT_TRUE(o.command.legs.empty());
}

TEST(MissionOptions, EveryProblemIsReportedTogether) {
  const std::string p = problemsOf({"--leg", "fly:1,2,3", "--leg", "vel:1,x,3", "--leg", "to:1,2"});
  EXPECT_NE(p.find("--leg 'fly:1,2,3' must be vel:E,N,SECONDS or to:E,N,SPEED"), std::string::npos) << p;
  EXPECT_NE(p.find("'x' is not a number"), std::string::npos) << p;
  EXPECT_NE(p.find("--leg 'to:1,2' needs three numbers: E,N,SPEED"), std::string::npos) << p;
  EXPECT_NE(problemsOf({}).find("nothing to send"), std::string::npos);
  EXPECT_NE(problemsOf({"--hold", "--leg", "vel:1,0,1"}).find("a hold has no legs"), std::string::npos);
}

TEST(MissionOptions, AnUnflyableMissionIsRefusedBeforeAnythingIsSent) {
  EXPECT_NE(problemsOf({"--leg", "vel:6,0,10"}).find("cannot be flown: leg 0 flies at 6 m/s"), std::string::npos)
      << problemsOf({"--leg", "vel:6,0,10"});
  EXPECT_NE(problemsOf({"--leg", "vel:1,0,0"}).find("duration_s = 0 must be > 0"), std::string::npos);
  EXPECT_NE(problemsOf({"--leg", "to:1,0,-1"}).find("speed_mps = -1 must be > 0"), std::string::npos);
  // The limit is the agents': raised with --max-speed
  EXPECT_EQ(problemsOf({"--leg", "vel:6,0,10", "--max-speed", "8"}), "");
}

TEST(MissionOptions, HelpWinsOverProblemsAndNamesTheForms) {
  EXPECT_TRUE(parseMissionOptions({"--help", "--leg", "bad"}).help);
  const std::string help = missionUsage();
  for (const char* needle : {"vel:E,N,SECONDS", "to:E,N,SPEED", "--hold", "swa/swarm/mission", "One writer"}) {
    EXPECT_NE(help.find(needle), std::string::npos) << needle;
  }
}

}  // namespace
}  // namespace swa::mission_tool

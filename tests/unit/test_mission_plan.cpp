// A swarm mission (issue #45): the plan's leg, velocity and path over time, legs built to pass through points, and
// the checks that refuse a plan before take-off.

#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "swa/agent/mission.h"

namespace swa::agent {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// East 2 s at 1 m/s, north 3 s at 2 m/s, back south-west 1 s: corners (0,0) (2,0) (2,6) (1,5), starts 0 2 5 6.
MissionPlan threeLegs() { return MissionPlan({{Vec2(1, 0), 2.0}, {Vec2(0, 2), 3.0}, {Vec2(-1, -1), 1.0}}); }

void expectNear(const Vec2& got, const Vec2& want, const char* what) {
  EXPECT_NEAR(got.x(), want.x(), 1e-9) << what;
  EXPECT_NEAR(got.y(), want.y(), 1e-9) << what;
}

TEST(MissionPlan, LegAtIsMinusOneBeforeTheStartThenEachLegThenTheHold) {
  const MissionPlan plan = threeLegs();
  EXPECT_EQ(plan.legCount(), 3u);
  EXPECT_DOUBLE_EQ(plan.duration_s(), 6.0);
  // A NaN time must not fall through the comparisons into some leg.
  EXPECT_EQ(plan.legAt(-0.1), -1);
  EXPECT_EQ(plan.legAt(-kInf), -1);
  EXPECT_EQ(plan.legAt(kNaN), -1);
  EXPECT_EQ(plan.legAt(0.0), 0);
  EXPECT_EQ(plan.legAt(1.0), 0);
  EXPECT_EQ(plan.legAt(3.5), 1);
  EXPECT_EQ(plan.legAt(5.5), 2);
  // Legs are half-open: a boundary belongs to the leg that starts there, the end to the hold.
  EXPECT_EQ(plan.legAt(2.0), 1);
  EXPECT_EQ(plan.legAt(5.0), 2);
  EXPECT_EQ(plan.legAt(6.0), 3);
  EXPECT_EQ(plan.legAt(1e9), 3);
  EXPECT_EQ(plan.legAt(kInf), 3);
}

TEST(MissionPlan, VelocityIsZeroOutsideTheLegs) {
  const MissionPlan plan = threeLegs();
  EXPECT_EQ(plan.velocityAt(-1.0), Vec2::Zero());
  EXPECT_EQ(plan.velocityAt(kNaN), Vec2::Zero());
  EXPECT_EQ(plan.velocityAt(0.0), Vec2(1, 0));
  EXPECT_EQ(plan.velocityAt(2.0), Vec2(0, 2));
  EXPECT_EQ(plan.velocityAt(5.9), Vec2(-1, -1));
  EXPECT_EQ(plan.velocityAt(6.0), Vec2::Zero());
  EXPECT_EQ(plan.velocityAt(100.0), Vec2::Zero());
}

TEST(MissionPlan, PathIsLinearInsideLegsContinuousAtBoundariesAndHoldsAtTheEnd) {
  const MissionPlan plan = threeLegs();
  expectNear(plan.pathAt(-1.0), Vec2::Zero(), "before the start");
  expectNear(plan.pathAt(0.0), Vec2::Zero(), "at the start");
  expectNear(plan.pathAt(1.5), Vec2(1.5, 0), "inside leg 0");
  expectNear(plan.pathAt(3.25), Vec2(2, 2.5), "inside leg 1");
  expectNear(plan.pathAt(5.5), Vec2(1.5, 5.5), "inside leg 2");
  // Continuity: just before each boundary the path is where the next leg starts from.
  for (const double b : {2.0, 5.0, 6.0}) {
    const Vec2 before = plan.pathAt(b - 1e-9);
    const Vec2 at = plan.pathAt(b);
    EXPECT_LT((at - before).norm(), 1e-8) << "boundary " << b;
  }
  expectNear(plan.endPoint(), Vec2(1, 5), "end point");
  expectNear(plan.pathAt(6.0), plan.endPoint(), "at the end");
  expectNear(plan.pathAt(1e6), plan.endPoint(), "long after the end");
}

TEST(MissionPlan, AnEmptyPlanHoldsAtTheOrigin) {
  const MissionPlan plan;
  EXPECT_TRUE(plan.empty());
  EXPECT_EQ(plan.legCount(), 0u);
  EXPECT_EQ(plan.duration_s(), 0.0);
  EXPECT_EQ(plan.legAt(0.0), -1);
  EXPECT_EQ(plan.velocityAt(1.0), Vec2::Zero());
  EXPECT_EQ(plan.pathAt(1.0), Vec2::Zero());
  EXPECT_EQ(plan.endPoint(), Vec2::Zero());
  EXPECT_TRUE(MissionPlan(std::vector<MissionLeg>{}).empty());
}

TEST(AppendLegTo, PathRunsThroughEveryPointAtTheGivenSpeed) {
  // GIVEN a plan that already flies 2 s north-east at (1, 1) m/s, ending at (2, 2)
  std::vector<MissionLeg> legs{{Vec2(1, 1), 2.0}};
  const std::vector<Vec2> points{Vec2(10, 2), Vec2(10, -3.7), Vec2(-4.2, 7.1)};
  const std::vector<double> speeds{2.0, 0.3, 4.5};
  // WHEN legs to three points are appended
  for (std::size_t k = 0; k < points.size(); ++k) ASSERT_TRUE(appendLegTo(legs, points[k], speeds[k]));
  // THEN each new leg starts where the plan was, flies at its speed, and ends exactly on its point: the legs are
  // built from the integral of the velocity, so no error accumulates from leg to leg
  ASSERT_EQ(legs.size(), 4u);
  const MissionPlan plan(legs);
  double t = legs[0].duration_s;
  expectNear(plan.pathAt(t), Vec2(2, 2), "end of the existing leg");
  for (std::size_t k = 0; k < points.size(); ++k) {
    const MissionLeg& leg = legs[k + 1];
    EXPECT_NEAR(leg.velocity_mps.norm(), speeds[k], 1e-9) << "leg " << k + 1;
    t += leg.duration_s;
    expectNear(plan.pathAt(t), points[k], "leg end");
  }
  expectNear(plan.endPoint(), points.back(), "end point");
}

TEST(AppendLegTo, APointThePlanIsAlreadyAtAddsNothing) {
  std::vector<MissionLeg> legs;
  // From an empty plan the start is the origin.
  EXPECT_TRUE(appendLegTo(legs, Vec2::Zero(), 1.0));
  EXPECT_TRUE(legs.empty());
  // (4, 0) at 2 m/s: every product is exact, so the plan ends exactly on the point.
  ASSERT_TRUE(appendLegTo(legs, Vec2(4, 0), 2.0));
  ASSERT_EQ(legs.size(), 1u);
  EXPECT_EQ(legs[0].duration_s, 2.0);
  // A zero-length leg would be refused by missionProblem, so a repeated point must not create one.
  EXPECT_TRUE(appendLegTo(legs, Vec2(4, 0), 3.0));
  EXPECT_EQ(legs.size(), 1u);
}

// After a leg to (3, 4) at 1 m/s the plan ends at (3.0000000000000004, 4) (0.2 is not exact in binary): repeating the
// point (a waypoint list that closes a loop) must add nothing, not a 2.2e-16 s leg at (-2, 0) m/s.
TEST(AppendLegTo, APointReachedWithRoundOffAddsNothing) {
  std::vector<MissionLeg> legs;
  ASSERT_TRUE(appendLegTo(legs, Vec2(3, 4), 1.0));
  EXPECT_TRUE(appendLegTo(legs, Vec2(3, 4), 2.0));
  EXPECT_EQ(legs.size(), 1u);
}

TEST(AppendLegTo, BadSpeedOrPointAppendsNothing) {
  std::vector<MissionLeg> legs{{Vec2(1, 0), 1.0}};
  for (const double speed : {0.0, -1.0, kNaN, kInf}) {
    EXPECT_FALSE(appendLegTo(legs, Vec2(5, 5), speed)) << "speed " << speed;
  }
  for (const Vec2& to : {Vec2(kNaN, 0), Vec2(0, kInf), Vec2(-kInf, kNaN)}) {
    EXPECT_FALSE(appendLegTo(legs, to, 1.0)) << to.transpose();
  }
  ASSERT_EQ(legs.size(), 1u);
  EXPECT_EQ(legs[0].velocity_mps, Vec2(1, 0));
}

MissionConfig goodConfig() {
  MissionConfig c;
  c.start = MissionStart::kTime;
  c.start_s = 12.0;
  c.max_speed_mps = 5.0;
  c.legs = {{Vec2(3, 4), 10.0}, {Vec2(-1, 0), 2.0}, {Vec2(0, 0), 5.0}};  // 5 m/s exactly is allowed; so is a hover
  return c;
}

// The message for `config`, or a note that there was none (so a failing substring check shows it).
std::string problem(const MissionConfig& config) {
  const std::optional<std::string> p = missionProblem(config);
  return p ? *p : std::string("<no problem>");
}

TEST(MissionProblem, AGoodPlanHasNone) {
  EXPECT_EQ(missionProblem(goodConfig()), std::nullopt);
  EXPECT_EQ(missionProblem(MissionConfig{}), std::nullopt);  // no legs: the swarm holds
}

TEST(MissionProblem, EachBadLegIsNamedByItsIndex) {
  MissionConfig c = goodConfig();
  c.legs[1].velocity_mps = Vec2(kNaN, 0);
  EXPECT_NE(problem(c).find("mission.legs[1]"), std::string::npos) << problem(c);
  c = goodConfig();
  c.legs[2].duration_s = kInf;
  EXPECT_NE(problem(c).find("mission.legs[2]"), std::string::npos) << problem(c);
  c = goodConfig();
  c.legs[1].duration_s = 0.0;
  EXPECT_NE(problem(c).find("mission.legs[1].duration_s"), std::string::npos) << problem(c);
  c = goodConfig();
  c.legs[0].duration_s = -1.0;
  EXPECT_NE(problem(c).find("mission.legs[0].duration_s"), std::string::npos) << problem(c);
  c = goodConfig();
  c.legs[2].velocity_mps = Vec2(3, 4.001);  // just above 5 m/s
  EXPECT_NE(problem(c).find("mission.legs[2]"), std::string::npos) << problem(c);
  EXPECT_NE(problem(c).find("max_speed_mps"), std::string::npos) << problem(c);
}

TEST(MissionProblem, BadStartOrSpeedLimitIsRefused) {
  for (const double start : {-0.5, kNaN, kInf}) {
    MissionConfig c = goodConfig();
    c.start_s = start;
    EXPECT_NE(problem(c).find("mission.start_s"), std::string::npos) << problem(c);
  }
  for (const double max_speed : {0.0, -2.0, kNaN}) {
    MissionConfig c = goodConfig();
    c.max_speed_mps = max_speed;
    EXPECT_NE(problem(c).find("mission.max_speed_mps"), std::string::npos) << problem(c);
  }
}

TEST(MissionProblem, TooManyLegsAreRefused) {
  MissionConfig c;
  c.legs.assign(kMaxMissionLegs, MissionLeg{Vec2(1, 0), 0.5});
  EXPECT_EQ(missionProblem(c), std::nullopt);  // the limit itself is allowed
  c.legs.push_back(MissionLeg{Vec2(1, 0), 0.5});
  EXPECT_NE(problem(c).find("mission.legs"), std::string::npos) << problem(c);
  EXPECT_NE(problem(c).find(std::to_string(kMaxMissionLegs + 1)), std::string::npos) << problem(c);
}

}  // namespace
}  // namespace swa::agent

namespace swa::agent {
namespace {

MissionCommandLeg velocityLeg(const Vec2& v, double duration_s) {
  return {MissionCommandLeg::Kind::kVelocity, v, duration_s, 0.0};
}
MissionCommandLeg toLeg(const Vec2& p, double speed_mps) { return {MissionCommandLeg::Kind::kTo, p, 0.0, speed_mps}; }

TEST(FlownUntil, CutsTheLegInForceAndHoldsAfterTheEnd) {
  const MissionPlan plan({{Vec2(2, 0), 10.0}, {Vec2(0, 1), 5.0}});
  // Inside the second leg: the first whole, the second cut
  const std::vector<MissionLeg> mid = flownUntil(plan, 12.0);
  ASSERT_EQ(mid.size(), 2u);
  EXPECT_EQ(mid[1].duration_s, 2.0);
  EXPECT_EQ(MissionPlan(mid).endPoint(), plan.pathAt(12.0));
  // After the end: both legs and a hold up to the time asked
  const std::vector<MissionLeg> after = flownUntil(plan, 20.0);
  ASSERT_EQ(after.size(), 3u);
  EXPECT_EQ(after[2].velocity_mps, Vec2::Zero());
  EXPECT_EQ(MissionPlan(after).duration_s(), 20.0);
  EXPECT_EQ(MissionPlan(after).endPoint(), plan.endPoint());
  // At or before the start: nothing was flown
  EXPECT_TRUE(flownUntil(plan, 0.0).empty());
  EXPECT_TRUE(flownUntil(plan, -1.0).empty());
}

TEST(AppendCommand, APlanReplacedMidLegKeepsItsPathAndGoesOnFromThePointItReached) {
  // GIVEN a plan east at 2 m/s for 10 s, replaced 4 s in by "to (8, 6) at 2 m/s, then north at 1 m/s for 3 s"
  const MissionPlan plan({{Vec2(2, 0), 10.0}});
  std::vector<MissionLeg> legs = flownUntil(plan, 4.0);
  MissionCommand command;
  command.legs = {toLeg(Vec2(8, 6), 2.0), velocityLeg(Vec2(0, 1), 3.0)};
  ASSERT_FALSE(missionCommandProblem(command, 5.0, 1e4));
  appendCommand(legs, command);
  const MissionPlan replaced(legs);
  // THEN the path until 4 s is the old one, the point is reached from (8, 0) straight north in 3 s, then 3 m more
  EXPECT_EQ(replaced.pathAt(2.0), plan.pathAt(2.0));
  EXPECT_NEAR((replaced.pathAt(7.0) - Vec2(8, 6)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((replaced.endPoint() - Vec2(8, 9)).norm(), 0.0, 1e-12);
  EXPECT_DOUBLE_EQ(replaced.duration_s(), 10.0);
}

TEST(MissionCommandProblem, AGoodCommandAndAHoldHaveNone) {
  MissionCommand go;
  go.legs = {velocityLeg(Vec2(3, 4), 10.0), toLeg(Vec2(100, 0), 5.0)};
  EXPECT_FALSE(missionCommandProblem(go, 5.0, 1e4));
  MissionCommand hold;
  hold.hold = true;
  EXPECT_FALSE(missionCommandProblem(hold, 5.0, 1e4));
}

TEST(MissionCommandProblem, EachBadCommandIsNamed) {
  const auto problem = [](MissionCommand c) { return missionCommandProblem(c, 5.0, 1e4).value_or("<none>"); };
  MissionCommand c;
  EXPECT_EQ(problem(c), "no legs and no hold");
  c.hold = true;
  c.legs = {velocityLeg(Vec2(1, 0), 1.0)};
  EXPECT_EQ(problem(c), "a hold with legs");
  c.hold = false;
  c.legs = {velocityLeg(Vec2(1, 0), 1.0), velocityLeg(Vec2(kNaN, 0), 1.0)};
  EXPECT_EQ(problem(c), "leg 1 is not finite");
  c.legs = {velocityLeg(Vec2(1, 0), 0.0)};
  EXPECT_EQ(problem(c), "leg 0 duration_s = 0 must be > 0");
  c.legs = {toLeg(Vec2(1, 0), -2.0)};
  EXPECT_EQ(problem(c), "leg 0 speed_mps = -2 must be > 0");
  c.legs = {velocityLeg(Vec2(3, 4.1), 1.0)};
  EXPECT_NE(problem(c).find("above mission.max_speed_mps = 5"), std::string::npos) << problem(c);
  c.legs = {toLeg(Vec2(1, 0), 6.0)};
  EXPECT_NE(problem(c).find("flies at 6 m/s"), std::string::npos) << problem(c);
  c.legs = {toLeg(Vec2(2e4, 0), 1.0)};
  EXPECT_NE(problem(c).find("beyond limits.max_abs_position_m = 10000"), std::string::npos) << problem(c);
  c.legs.assign(kMaxMissionLegs + 1, velocityLeg(Vec2(1, 0), 1.0));
  EXPECT_EQ(problem(c), "1001 legs; at most 1000");
}

}  // namespace
}  // namespace swa::agent

// Bad detection input at the Agent facade: sets larger than limits.max_detections, non-finite or implausible
// positions and covariances, out-of-range IDs, sets before any heading and stamps that do not advance are rejected
// and counted in Diagnostics::rejected without any lasting effect; values at the limits are accepted. Also: an
// anonymous detection with an absurd covariance must not hang the agent. Helpers and the `Twins` fixture:
// agent_input_support.h.

#include <climits>
#include <cmath>
#include <cstddef>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "agent_input_support.h"
#include "swa/agent/agent.h"

namespace swa::agent {
namespace {

using namespace testing;  // agent_input_support.h

// ===============================================================================================================
// Detections

TEST(AgentInputDetections, SetLargerThanBoundIsRejectedWholeOncePerSet) {
  // GIVEN an agent with a heading and no tracks, limits.max_detections = 64
  Agent agent(configFor(Mode::kSwa));
  giveHeading(agent);
  const std::size_t max = agent.config().limits.max_detections;
  ASSERT_EQ(max, 64u);

  // WHEN two sets of 65 valid, distinct detections arrive
  for (int k = 0; k < 2; ++k) {
    DetectionSet big;
    big.stamp_ns = kT0 + (k + 1) * kMs;
    for (std::size_t i = 0; i <= max; ++i) {
      big.detections.push_back(det(static_cast<int>(i), 5.0 + static_cast<double>(i), 1.0));
    }
    agent.onDetections(big);
  }

  // THEN oversize counts 1 per set (2), nothing else, and nothing is tracked
  expectCounters(agent.diagnostics().rejected, only(&RejectCounters::oversize, 2));
  EXPECT_TRUE(agent.bank().tracks().empty());
  EXPECT_EQ(agent.diagnostics().tentative_tracks, 0);
  EXPECT_EQ(agent.diagnostics().confirmed_tracks, 0);

  // AND a valid set with the same stamp as a rejected one is still accepted (the stamp was not consumed)
  agent.onDetections(detectionSet(kT0 + 2 * kMs, {det(3, 4.0, 0.0)}));
  expectCounters(agent.diagnostics().rejected, only(&RejectCounters::oversize, 2));
  EXPECT_NE(agent.bank().find(3), nullptr);
}

TEST(AgentInputDetections, OversizeSetChangesNothingInATrackingAgent) {
  // GIVEN two anchored agents tracking on the same stream
  Twins tw(Mode::kAnchored);
  ASSERT_NO_FATAL_FAILURE(tw.expectWarmedUp());
  const DetectionSet good = tw.advanceTo(Event::Kind::kDetections).detections;
  // WHEN one gets, before the next good set, a set of 65 detections of the known neighbours with the same stamp
  DetectionSet big;
  big.stamp_ns = good.stamp_ns;
  while (big.detections.size() <= tw.config.limits.max_detections)
    for (const Detection& d : good.detections) big.detections.push_back(d);
  big.detections.resize(tw.config.limits.max_detections + 1);
  tw.dut.onDetections(big);
  // THEN oversize == 1 and nothing else changed
  tw.expectOnlyRejected(&RejectCounters::oversize, 1, /*extra_commands=*/0);
}

TEST(AgentInputDetections, SetOfExactlyTheBoundIsAccepted) {
  // GIVEN an agent with a heading
  Agent agent(configFor(Mode::kSwa));
  giveHeading(agent);
  // WHEN a set of exactly 64 valid detections with distinct IDs arrives
  DetectionSet set = detectionSet(kT0 + kMs);
  for (int i = 0; i < 64; ++i) set.detections.push_back(det(i, 5.0 + i, -2.0));
  agent.onDetections(set);
  // THEN nothing is rejected and all 64 are tracked (tentative)
  expectCounters(agent.diagnostics().rejected, RejectCounters{});
  EXPECT_EQ(agent.bank().tracks().size(), 64u);
  EXPECT_EQ(agent.diagnostics().tentative_tracks, 64);
  for (int i = 0; i < 64; ++i) EXPECT_NE(agent.bank().find(i), nullptr) << i;
}

TEST(AgentInputDetections, NonFinitePositionDropsOnlyThatDetection) {
  // GIVEN two anchored agents tracking on the same stream
  Twins tw(Mode::kAnchored);
  ASSERT_NO_FATAL_FAILURE(tw.expectWarmedUp());
  const DetectionSet set = tw.takeNext(Event::Kind::kDetections).detections;
  // WHEN one gets the next set with extra detections of new IDs 20..23 with NaN x, inf y, -inf x, NaN both, and
  // the other the set without them
  const std::vector<Detection> bad = {det(20, kNan, 1.0), det(21, 1.0, kInf), det(22, -kInf, 0.0), det(23, kNan, kNan)};
  tw.feedDetections(set, bad);
  // THEN nonfinite == 4, nothing else; the bad IDs are not tracked and the good detections of the same set were used
  expectCounters(tw.dut.diagnostics().rejected, only(&RejectCounters::nonfinite, 4));
  for (int id = 20; id <= 23; ++id) EXPECT_EQ(tw.dut.bank().find(id), nullptr) << id;
  for (const Detection& d : set.detections) {
    const Track* t = tw.dut.bank().find(d.target_id);
    ASSERT_NE(t, nullptr);
    EXPECT_EQ(t->last_detection_ns, set.stamp_ns) << "good detection " << d.target_id << " of the set not used";
  }
  tw.expectNoLastingEffect(0);
}

TEST(AgentInputDetections, NonFiniteCovarianceIsNonfinite) {
  // GIVEN two anchored agents tracking on the same stream
  Twins tw(Mode::kAnchored);
  ASSERT_NO_FATAL_FAILURE(tw.expectWarmedUp());
  const DetectionSet set = tw.takeNext(Event::Kind::kDetections).detections;
  // WHEN one gets the next set with extra detections (valid positions, new IDs) whose covariance has a NaN
  // (diagonal, off-diagonal), an inf, or is all NaN
  const std::vector<Detection> bad = {
      det(20, 3.0, 1.0, mat(kNan, 0.0, 0.0, 0.1)), det(21, 3.0, 1.0, mat(0.1, kNan, kNan, 0.1)),
      det(22, 3.0, 1.0, mat(0.1, 0.0, 0.0, kInf)), det(23, 3.0, 1.0, Mat2::Constant(kNan)),
      // an existing neighbour's ID: the bad covariance must not touch its track either
      det(set.detections.front().target_id, set.detections.front().position_body_m.x(),
          set.detections.front().position_body_m.y(), mat(0.1, 0.0, 0.0, kNan))};
  tw.feedDetections(set, bad);
  // THEN nonfinite == 5, nothing else, and no effect
  expectCounters(tw.dut.diagnostics().rejected, only(&RejectCounters::nonfinite, 5));
  for (int id = 20; id <= 23; ++id) EXPECT_EQ(tw.dut.bank().find(id), nullptr) << id;
  tw.expectNoLastingEffect(0);
}

TEST(AgentInputDetections, NonSpdCovarianceIsImplausible) {
  // GIVEN two anchored agents tracking on the same stream
  Twins tw(Mode::kAnchored);
  ASSERT_NO_FATAL_FAILURE(tw.expectWarmedUp());
  const DetectionSet set = tw.takeNext(Event::Kind::kDetections).detections;
  // WHEN one gets the next set with extra detections whose covariance is finite but not a covariance: negative
  // variance (first, second, both), asymmetric, symmetric indefinite, zero, and positive semi-definite (singular)
  const std::vector<Detection> bad = {
      det(20, 3.0, 1.0, mat(-0.1, 0.0, 0.0, 0.1)),  det(21, 3.0, 1.0, mat(0.1, 0.0, 0.0, -0.1)),
      det(22, 3.0, 1.0, mat(-0.1, 0.0, 0.0, -0.1)), det(23, 3.0, 1.0, mat(0.1, 0.05, -0.05, 0.1)),
      det(24, 3.0, 1.0, mat(0.1, 0.5, 0.5, 0.1)),   det(25, 3.0, 1.0, Mat2::Zero()),
      det(26, 3.0, 1.0, mat(0.1, 0.1, 0.1, 0.1))};
  tw.feedDetections(set, bad);
  // THEN implausible == 7, nothing else, and no effect
  expectCounters(tw.dut.diagnostics().rejected, only(&RejectCounters::implausible, 7));
  for (int id = 20; id <= 26; ++id) EXPECT_EQ(tw.dut.bank().find(id), nullptr) << id;
  tw.expectNoLastingEffect(0);
}

TEST(AgentInputDetections, PositionBeyondLimitIsImplausible) {
  // GIVEN two anchored agents tracking on the same stream, max_abs_position_m = 1e6
  Twins tw(Mode::kAnchored);
  ASSERT_NO_FATAL_FAILURE(tw.expectWarmedUp());
  const double max_pos = tw.config.limits.max_abs_position_m;
  const DetectionSet set = tw.takeNext(Event::Kind::kDetections).detections;
  // WHEN one gets extra detections farther than the limit (just beyond on an axis, diagonally, 1e300, and DBL_MAX
  // whose norm overflows)
  const double big = std::numeric_limits<double>::max();
  const std::vector<Detection> bad = {det(20, std::nextafter(max_pos, 2e6), 0.0),
                                      det(21, 0.0, -2e6),
                                      det(22, 0.75e6, -0.75e6),
                                      det(23, 1e300, 1e300),
                                      det(24, big, -big),
                                      det(kAnonymousId, 1e300, 0.0)};
  tw.feedDetections(set, bad);
  // THEN implausible == 6, nothing else, and no effect
  tw.expectOnlyRejected(&RejectCounters::implausible, 6, /*extra_commands=*/0);
}

TEST(AgentInputDetections, PositionAtLimitIsAcceptedButNotANeighbour) {
  // GIVEN an agent with a heading
  Agent agent(configFor(Mode::kSwa));
  giveHeading(agent);
  // WHEN a detection lies exactly at max_abs_position_m
  agent.onDetections(detectionSet(kT0 + kMs, {det(9, agent.config().limits.max_abs_position_m, 0.0)}));
  // THEN it is accepted and tracked
  expectCounters(agent.diagnostics().rejected, RejectCounters{});
  EXPECT_NE(agent.bank().find(9), nullptr);
  EXPECT_EQ(agent.diagnostics().neighbour_count, 0);
}

TEST(AgentInputDetections, IdOutsideRangeIsBadId) {
  // GIVEN two anchored agents tracking on the same stream, max_target_id = 255 (the default)
  Twins tw(Mode::kAnchored);
  ASSERT_NO_FATAL_FAILURE(tw.expectWarmedUp());
  const int max_id = tw.config.limits.max_target_id;
  const DetectionSet set = tw.takeNext(Event::Kind::kDetections).detections;
  // WHEN one gets extra, otherwise valid detections with IDs -2, -1000, INT_MIN, max+1, INT_MAX and the first
  // anonymous track id
  const std::vector<Detection> bad = {det(-2, 3.0, 1.0),      det(-1000, 3.0, 1.0),
                                      det(INT_MIN, 3.0, 1.0), det(max_id + 1, 3.0, 1.0),
                                      det(INT_MAX, 3.0, 1.0), det(kFirstAnonymousTrackId, 3.0, 1.0)};
  tw.feedDetections(set, bad);
  // THEN bad_id == 6, nothing else, and no effect
  tw.expectOnlyRejected(&RejectCounters::bad_id, 6, /*extra_commands=*/0);
}

TEST(AgentInputDetections, IdsAtTheEdgesOfTheRangeAreAccepted) {
  // GIVEN an agent with a heading
  Agent agent(configFor(Mode::kSwa));
  giveHeading(agent);
  // WHEN detections with IDs 0, max_target_id and anonymous (-1) arrive
  agent.onDetections(detectionSet(
      kT0 + kMs, {det(0, 5.0, 0.0), det(agent.config().limits.max_target_id, 0.0, 5.0), det(kAnonymousId, -5.0, 0.0)}));
  // THEN nothing is rejected and three tracks exist
  expectCounters(agent.diagnostics().rejected, RejectCounters{});
  EXPECT_NE(agent.bank().find(0), nullptr);
  EXPECT_NE(agent.bank().find(agent.config().limits.max_target_id), nullptr);
  EXPECT_EQ(agent.bank().tracks().size(), 3u);
}

TEST(AgentInputDetections, DetectionsBeforeAnyAcceptedImuHaveNoHeading) {
  // GIVEN a fresh agent (no IMU sample yet)
  Agent agent(configFor(Mode::kSwa));
  const DetectionSet set = detectionSet(kT0, {det(1, 5.0, 0.0), det(2, 0.0, 5.0)});

  // WHEN a valid set of two detections arrives
  agent.onDetections(set);
  // THEN no_heading counts the set once, nothing is tracked
  expectCounters(agent.diagnostics().rejected, only(&RejectCounters::no_heading, 1));
  EXPECT_TRUE(agent.bank().tracks().empty());

  // WHEN a rejected IMU sample (NaN heading) arrives and then the set again
  ImuSample bad;
  bad.stamp_ns = kT0 + kMs;
  bad.heading_rad = kNan;
  agent.onImu(bad);
  agent.onDetections(set);
  // THEN the rejected IMU did not give a heading either
  RejectCounters want;
  want.no_heading = 2;
  want.nonfinite = 1;
  expectCounters(agent.diagnostics().rejected, want);
  EXPECT_TRUE(agent.bank().tracks().empty());

  // WHEN a good IMU sample arrives, then the same set with the same stamp
  ImuSample good;
  good.stamp_ns = kT0 + 2 * kMs;
  agent.onImu(good);
  agent.onDetections(set);
  // THEN it is accepted (the no_heading rejections did not consume the stamp)
  expectCounters(agent.diagnostics().rejected, want);
  EXPECT_EQ(agent.bank().tracks().size(), 2u);
}

TEST(AgentInputDetections, SetStampNotIncreasingIsOutOfOrder) {
  // GIVEN two anchored agents tracking on the same stream, the last accepted detection set stamped T
  Twins tw(Mode::kAnchored);
  ASSERT_NO_FATAL_FAILURE(tw.expectWarmedUp());
  const Event next = tw.takeNext(Event::Kind::kDetections);
  tw.ref.onDetections(next.detections);
  tw.dut.onDetections(next.detections);
  const StampNs last = next.detections.stamp_ns;

  // WHEN one gets valid sets stamped T (equal), T - 1 ns and T - 2 s, with shifted positions that would move the
  // tracks if used
  for (StampNs st : {last, last - 1, last - 2 * kSec}) {
    DetectionSet s = next.detections;
    s.stamp_ns = st;
    for (Detection& d : s.detections) d.position_body_m += Vec2(1.0, 1.0);
    tw.dut.onDetections(s);
  }
  // THEN out_of_order == 3 (once per set), nothing else, and no effect
  tw.expectOnlyRejected(&RejectCounters::out_of_order, 3, /*extra_commands=*/0);
}

TEST(AgentInputDetections, SetOlderThanLatestImuIsNotOutOfOrder) {
  // GIVEN an agent whose IMU is at T
  Agent agent(configFor(Mode::kSwa));
  giveHeading(agent, kT0 + 100 * kMs);
  // WHEN a detection set stamped 50 ms before T arrives (sensor latency; stamps are ordered per stream)
  agent.onDetections(detectionSet(kT0 + 50 * kMs, {det(1, 5.0, 0.0)}));
  // THEN it is accepted
  expectCounters(agent.diagnostics().rejected, RejectCounters{});
  EXPECT_NE(agent.bank().find(1), nullptr);
}

// The assignment cost of an anonymous detection is mahalanobis2 + ln det S. A detection covariance of 1e300 m^2
// passes isCovariance() (its determinant overflows to +inf, and inf > 0), so ln det S = +inf reaches the Hungarian
// solver, whose potentials become inf - inf = NaN and whose augmenting search never terminates.
TEST(AgentInputDetections, AnonymousDetectionWithAbsurdCovarianceDoesNotHangTheAgent) {
  for (const double variance : {1e155, 1e300}) {
    std::ostringstream label;
    label << "variance " << variance << " m^2";
    SCOPED_TRACE(label.str());
    // GIVEN an agent with one tentative anonymous track 5 m ahead
    auto scenario = [variance](Agent& agent) {
      giveHeading(agent);
      DetectionSet set = detectionSet(kT0 + kMs, {det(kAnonymousId, 5.0, 0.0)});
      agent.onDetections(set);
      // WHEN an anonymous detection at the same place arrives with covariance variance * I (finite, SPD)
      set.stamp_ns += 100 * kMs;
      set.detections = {det(kAnonymousId, 5.0, 0.0, Mat2(Mat2::Identity() * variance))};
      agent.onDetections(set);
      // AND then an ordinary one
      set.stamp_ns += 100 * kMs;
      set.detections = {det(kAnonymousId, 5.0, 0.0)};
      agent.onDetections(set);
    };
    // THEN the agent returns (checked in a child process with a deadline)
    const std::string hang = runWithDeadline(5, [&] {
      Agent agent(configFor(Mode::kSwa));
      scenario(agent);
    });
    EXPECT_EQ(hang, "");
    if (!hang.empty()) continue;
    // AND the detection was either rejected as implausible or used harmlessly: tracks finite, nothing else counted
    Agent agent(configFor(Mode::kSwa));
    scenario(agent);
    const RejectCounters& r = agent.diagnostics().rejected;
    EXPECT_EQ(r.total(), r.implausible);
    EXPECT_LE(r.implausible, 1u);
    EXPECT_TRUE(finiteTracks(agent.bank()));
    EXPECT_FALSE(agent.bank().tracks().empty());
  }
}

}  // namespace
}  // namespace swa::agent

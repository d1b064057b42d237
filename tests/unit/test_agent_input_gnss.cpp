// Bad GNSS input at the Agent facade: valid-flagged fixes with non-finite values, non-positive or absurd std, far
// positions and stamps that do not advance are rejected and counted in Diagnostics::rejected without any lasting
// effect; invalid fixes with garbage fields are not errors. Helpers and the `Twins` fixture: agent_input_support.h.

#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

#include "agent_input_support.h"
#include "swa/agent/agent.h"

namespace swa::agent {
namespace {

using namespace testing;  // agent_input_support.h

// ===============================================================================================================
// GNSS

TEST(AgentInputGnss, ValidFixWithNonFiniteValuesIsNonfinite) {
  // GIVEN two anchored agents tracking on the same stream (GNSS in use)
  Twins tw(Mode::kAnchored);
  ASSERT_NO_FATAL_FAILURE(tw.expectWarmedUp());
  const StampNs next = tw.nextStamp(Event::Kind::kGnss);
  ASSERT_TRUE(tw.dut.diagnostics().gnss_valid);
  // WHEN one gets valid-flagged fixes with NaN x, inf y, NaN std, inf std (stamped like the next good fix)
  std::vector<GnssSample> bad = validFixes(4, next);
  bad[0].position_m.x() = kNan;
  bad[1].position_m.y() = kInf;
  bad[2].std_m = kNan;
  bad[3].std_m = kInf;
  for (const GnssSample& g : bad) tw.dut.onGnss(g);
  // THEN nonfinite == 4, nothing else, and no effect
  tw.expectOnlyRejected(&RejectCounters::nonfinite, 4, /*extra_commands=*/0);
}

TEST(AgentInputGnss, NonPositiveStdOrFarPositionIsImplausible) {
  // GIVEN two anchored agents tracking on the same stream
  Twins tw(Mode::kAnchored);
  ASSERT_NO_FATAL_FAILURE(tw.expectWarmedUp());
  const StampNs next = tw.nextStamp(Event::Kind::kGnss);
  // WHEN one gets valid-flagged fixes with std 0, -0, -1, and a position beyond max_abs_position_m (1e6 + 1 and
  // 1e300)
  std::vector<GnssSample> bad = validFixes(5, next);
  bad[0].std_m = 0.0;
  bad[1].std_m = -0.0;
  bad[2].std_m = -1.0;
  bad[3].position_m = Vec2(tw.config.limits.max_abs_position_m + 1.0, 0.0);
  bad[4].position_m = Vec2(1e300, 1e300);
  for (const GnssSample& g : bad) tw.dut.onGnss(g);
  // THEN implausible == 5, nothing else, and no effect
  tw.expectOnlyRejected(&RejectCounters::implausible, 5, /*extra_commands=*/0);
}

TEST(AgentInputGnss, StampNotAfterPreviousIsOutOfOrder) {
  // GIVEN two anchored agents tracking on the same stream, last fix at T
  Twins tw(Mode::kAnchored);
  ASSERT_NO_FATAL_FAILURE(tw.expectWarmedUp());
  const Event next = tw.takeNext(Event::Kind::kGnss);
  tw.ref.onGnss(next.gnss);
  tw.dut.onGnss(next.gnss);
  // WHEN one gets valid fixes stamped T, T - 1 ns and T - 3 s that would pull the estimate 5 m if used, and one
  // invalid fix stamped T - 1 ns
  for (StampNs st : {next.gnss.stamp_ns, next.gnss.stamp_ns - 1, next.gnss.stamp_ns - 3 * kSec}) {
    GnssSample g = next.gnss;
    g.stamp_ns = st;
    g.position_m += Vec2(5.0, 0.0);
    tw.dut.onGnss(g);
  }
  GnssSample lost = next.gnss;
  lost.stamp_ns = next.gnss.stamp_ns - 1;
  lost.valid = false;
  tw.dut.onGnss(lost);
  // THEN out_of_order == 4, nothing else, and no effect (the stale invalid fix did not clear gnss_valid either)
  expectCounters(tw.dut.diagnostics().rejected, only(&RejectCounters::out_of_order, 4));
  EXPECT_TRUE(tw.dut.diagnostics().gnss_valid);
  tw.expectNoLastingEffect(0);
}

TEST(AgentInputGnss, InvalidFixWithGarbageFieldsIsNotAnError) {
  // GIVEN two anchored agents tracking on the same stream
  Twins tw(Mode::kAnchored);
  ASSERT_NO_FATAL_FAILURE(tw.expectWarmedUp());
  const Event next = tw.takeNext(Event::Kind::kGnss);
  // WHEN the receiver loses its fix: `dut` gets valid=false with NaN / inf / negative garbage in every field, `ref`
  // gets valid=false with clean zeros, both at the same stamp
  GnssSample garbage;
  garbage.stamp_ns = next.gnss.stamp_ns;
  garbage.valid = false;
  garbage.position_m = Vec2(kNan, -kInf);
  garbage.std_m = kNan;
  GnssSample clean;  // default position and std
  clean.stamp_ns = next.gnss.stamp_ns;
  clean.valid = false;
  tw.dut.onGnss(garbage);
  tw.ref.onGnss(clean);
  // THEN nothing is rejected, both report no valid GNSS (diagnostics are refreshed by the next IMU sample), the
  // estimate is finite, and the garbage had no effect beyond "no fix": the agents stay bit-identical from here on
  expectCounters(tw.dut.diagnostics().rejected, RejectCounters{});
  const Event imu = tw.takeNext(Event::Kind::kImu);
  feed(tw.ref, imu);
  feed(tw.dut, imu);
  EXPECT_FALSE(tw.dut.diagnostics().gnss_valid);
  EXPECT_TRUE(allFinite(tw.dut.diagnostics().position_m));
  EXPECT_TRUE(allFinite(tw.dut.diagnostics().position_cov_m2));
  // More lost fixes, each with garbage, then the receiver recovers (the rest of the stream has valid fixes).
  for (int i = 1; i <= 3; ++i) {
    garbage.stamp_ns = next.gnss.stamp_ns + i;
    garbage.std_m = -kInf;
    clean.stamp_ns = garbage.stamp_ns;
    tw.dut.onGnss(garbage);
    tw.ref.onGnss(clean);
  }
  expectCounters(tw.dut.diagnostics().rejected, RejectCounters{});
  tw.expectNoLastingEffect(0);
  EXPECT_TRUE(tw.dut.diagnostics().gnss_valid) << "the later valid fixes must be used again";
}

// A fix whose std is finite and positive but absurd (1e300 m): its variance overflows to inf. The counter docs list
// "GNSS std" under implausible ("finite but physically impossible"), so it is rejected and counted like std <= 0,
// and above all it must not wreck the absolute estimator.
TEST(AgentInputGnss, AbsurdStdDoesNotPoisonTheAbsoluteEstimator) {
  for (const bool first_fix : {true, false}) {
    SCOPED_TRACE(first_fix ? "absurd std on the very first (hold-point) fix" : "absurd std on a later fix");
    // GIVEN a standalone agent at the take-off point
    Agent agent(configFor(Mode::kStandalone));
    StampNs t = kT0;
    auto imuAt = [&](StampNs st) {
      ImuSample s;
      s.stamp_ns = st;
      return agent.onImu(s);
    };
    auto fix = [&](StampNs st, const Vec2& p, double std_m) {
      GnssSample g;
      g.stamp_ns = st;
      g.valid = true;
      g.position_m = p;
      g.std_m = std_m;
      agent.onGnss(g);
    };
    imuAt(t);
    if (!first_fix) {
      fix(t += kMs, Vec2(0.0, 0.0), 0.5);
      imuAt(t += 10 * kMs);
    }
    // WHEN a valid-flagged fix reports std = 1e300 m
    fix(t += kMs, Vec2(0.0, 0.0), 1e300);
    // THEN it is rejected as implausible, once, and nothing else is counted
    expectCounters(agent.diagnostics().rejected, only(&RejectCounters::implausible, 1));
    // AND then good fixes (std 0.5 m) put the UAV 3 m east of the hold point for 5 s
    if (first_fix) fix(t += 50 * kMs, Vec2(0.0, 0.0), 0.5);  // the hold point, if the absurd one was not used
    VelocityCommand last;
    for (int i = 0; i < 500; ++i) {
      last = imuAt(t += 10 * kMs);
      if (i % 10 == 0) fix(t += kMs, Vec2(3.0, 0.0), 0.5);
    }
    expectCounters(agent.diagnostics().rejected, only(&RejectCounters::implausible, 1));
    // AND the estimator's covariance is finite and the good fixes were used: the estimate is near +3 m and the
    // command points west, back to the hold point
    const Diagnostics& d = agent.diagnostics();
    EXPECT_TRUE(allFinite(d.position_cov_m2)) << d.position_cov_m2;
    EXPECT_TRUE(allFinite(d.velocity_cov_m2ps2)) << d.velocity_cov_m2ps2;
    EXPECT_TRUE(allFinite(d.position_m));
    EXPECT_GT(d.position_m.x(), 1.0) << "good fixes after the absurd one were ignored";
    EXPECT_LT(last.velocity_mps.x(), -0.1) << "standalone agent does not steer back to its hold point";
  }
}

// ArduPilot sends no GNSS while its receiver is unhealthy: the stream falls silent for longer than the stamp window
// and comes back on the IMU's timeline. Its first fixes are news, not future stamps (before: the first three were
// rejected as such, and the regained GNSS used 0.3 s late).
TEST(AgentInputGnss, AFixAfterASilenceIsUsedAtOnceWhenItIsOnTheImusTimeline) {
  // GIVEN an anchored agent with IMU at 100 Hz and fixes at 10 Hz for 1 s, then a loss, then 2.5 s without any fix
  Agent agent(configFor(Mode::kAnchored));
  StampNs t = kT0;
  GnssSample g;
  g.valid = true;
  g.std_m = 0.5;
  for (int i = 0; i < 100; ++i) {
    ImuSample s;
    s.stamp_ns = t += 10 * kMs;
    agent.onImu(s);
    g.stamp_ns = t;
    if (i % 10 == 0) agent.onGnss(g);
  }
  GnssSample lost;
  lost.stamp_ns = t;
  agent.onGnss(lost);
  for (int i = 0; i < 250; ++i) {
    ImuSample s;
    s.stamp_ns = t += 10 * kMs;
    agent.onImu(s);
  }
  ASSERT_FALSE(agent.diagnostics().gnss_valid);
  // WHEN a fix comes at the IMU's time
  g.stamp_ns = t;
  agent.onGnss(g);
  // THEN it is used at once, and nothing is counted as rejected
  EXPECT_TRUE(agent.diagnostics().gnss_valid);
  expectCounters(agent.diagnostics().rejected, RejectCounters{});
  // AND a fix further ahead of the IMU than the window is still a future one
  g.stamp_ns = t + 2 * kSec;
  agent.onGnss(g);
  EXPECT_EQ(agent.diagnostics().rejected.future, 1u);
}

}  // namespace
}  // namespace swa::agent

// Bad IMU input at the Agent facade: non-finite attitude, tilt beyond limits.max_tilt_rad and stamps that do not
// advance are rejected and counted in Diagnostics::rejected, answered with the previous (finite) command, and leave
// no lasting effect on the agent. Helpers and the `Twins` fixture: agent_input_support.h.

#include <cmath>
#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

#include "agent_input_support.h"
#include "swa/agent/agent.h"

namespace swa::agent {
namespace {

using namespace testing;  // agent_input_support.h

// ===============================================================================================================
// IMU

TEST(AgentInputImu, NonFiniteAttitudeIsCountedAsNonfiniteAndChangesNothing) {
  // GIVEN two anchored agents tracking on the same stream
  Twins tw(Mode::kAnchored);
  ASSERT_NO_FATAL_FAILURE(tw.expectWarmedUp());
  const StampNs next = tw.nextStamp(Event::Kind::kImu);
  const Vec2 previous = tw.last_command.velocity_mps;

  // WHEN one of them gets IMU samples with a NaN roll, an inf pitch, a NaN heading, a -inf heading (each with the
  // stamp of the next good sample, so a consumed stamp would show up as an out_of_order later)
  std::vector<ImuSample> bad(4);
  bad[0].roll_rad = kNan;
  bad[1].pitch_rad = kInf;
  bad[2].heading_rad = kNan;
  bad[3].heading_rad = -kInf;
  for (ImuSample& s : bad) {
    s.stamp_ns = next;
    const VelocityCommand c = tw.dut.onImu(s);
    // THEN each is still answered, with the previous command, which is finite
    EXPECT_TRUE(sameBits(c.velocity_mps, previous)) << c.velocity_mps.transpose() << " vs " << previous.transpose();
    EXPECT_TRUE(allFinite(c.velocity_mps));
  }

  // THEN exactly nonfinite went up, by 4, and nothing else changed
  tw.expectOnlyRejected(&RejectCounters::nonfinite, 4, /*extra_commands=*/4);
}

TEST(AgentInputImu, TiltBeyondLimitIsCountedAsImplausibleAndChangesNothing) {
  // GIVEN two anchored agents tracking on the same stream, max_tilt_rad (default 1.4)
  Twins tw(Mode::kAnchored);
  ASSERT_NO_FATAL_FAILURE(tw.expectWarmedUp());
  const double max_tilt = tw.config.limits.max_tilt_rad;
  const StampNs next = tw.nextStamp(Event::Kind::kImu);
  const Vec2 previous = tw.last_command.velocity_mps;

  // WHEN one of them gets finite IMU samples with |roll| or |pitch| just above, and far above, the limit
  std::vector<ImuSample> bad(5);
  bad[0].roll_rad = std::nextafter(max_tilt, 10.0);
  bad[1].roll_rad = -(max_tilt + 0.4);
  bad[2].pitch_rad = std::nextafter(-max_tilt, -10.0);
  bad[3].pitch_rad = 1e300;
  bad[4].roll_rad = max_tilt + 0.1;
  bad[4].pitch_rad = -(max_tilt + 0.1);
  for (ImuSample& s : bad) {
    s.stamp_ns = next;
    s.heading_rad = 0.3;
    const VelocityCommand c = tw.dut.onImu(s);
    EXPECT_TRUE(sameBits(c.velocity_mps, previous));
  }

  // THEN exactly implausible went up, by 5, and nothing else changed
  tw.expectOnlyRejected(&RejectCounters::implausible, 5, /*extra_commands=*/5);
}

TEST(AgentInputImu, TiltExactlyAtLimitIsAccepted) {
  // GIVEN a fresh agent
  Agent agent(configFor(Mode::kSwa));
  const double max_tilt = agent.config().limits.max_tilt_rad;
  // WHEN IMU samples have |roll| and |pitch| exactly at the limit
  ImuSample s;
  s.stamp_ns = kT0;
  s.roll_rad = max_tilt;
  s.pitch_rad = -max_tilt;
  agent.onImu(s);
  // THEN nothing is rejected, and the sample gave a heading (a detection set is accepted afterwards)
  agent.onDetections(detectionSet(kT0 + kMs, {det(1, 5.0, 0.0)}));
  expectCounters(agent.diagnostics().rejected, RejectCounters{});
  EXPECT_NE(agent.bank().find(1), nullptr);
}

TEST(AgentInputImu, StampNotAfterPreviousIsOutOfOrderAndAnsweredWithPreviousCommand) {
  // GIVEN two anchored agents tracking on the same stream, the last IMU at stamp T
  Twins tw(Mode::kAnchored);
  ASSERT_NO_FATAL_FAILURE(tw.expectWarmedUp());
  const StampNs last = tw.last_command.stamp_ns;
  const Vec2 previous = tw.last_command.velocity_mps;
  const std::uint64_t seq = tw.dut.diagnostics().commands;

  // WHEN one of them gets valid-looking IMU samples stamped T (equal), T - 1 ns and T - 1 s, with an attitude that
  // would change the command if used
  const StampNs stamps[] = {last, last - 1, last - kSec};
  for (StampNs st : stamps) {
    ImuSample s;
    s.stamp_ns = st;
    s.roll_rad = 0.5;
    s.pitch_rad = -0.5;
    s.heading_rad = 2.0;
    const VelocityCommand c = tw.dut.onImu(s);
    // THEN each is answered with exactly the previous command, finite and within saturation
    EXPECT_TRUE(sameBits(c.velocity_mps, previous)) << c.velocity_mps.transpose() << " vs " << previous.transpose();
    EXPECT_TRUE(allFinite(c.velocity_mps));
    EXPECT_LE(c.velocity_mps.norm(), tw.config.control.v_max_mps);
    EXPECT_EQ(c.answered_stamp_ns, st);
  }
  EXPECT_EQ(tw.dut.diagnostics().commands, seq + 3);

  // THEN exactly out_of_order went up, by 3, and nothing else changed
  tw.expectOnlyRejected(&RejectCounters::out_of_order, 3, /*extra_commands=*/3);
}

TEST(AgentInputImu, RejectedImuBeforeAnyGoodOneAnswersWithZeroCommand) {
  // GIVEN a fresh agent
  Agent agent(configFor(Mode::kAnchored));
  // WHEN its very first IMU samples are non-finite / implausible
  ImuSample a;
  a.stamp_ns = kT0;
  a.roll_rad = kNan;
  ImuSample b;
  b.stamp_ns = kT0 + kMs;
  b.pitch_rad = 3.0;
  const VelocityCommand ca = agent.onImu(a);
  const VelocityCommand cb = agent.onImu(b);
  // THEN they are answered with a hover command and counted once each
  EXPECT_TRUE(sameBits(ca.velocity_mps, Vec2::Zero()));
  EXPECT_TRUE(sameBits(cb.velocity_mps, Vec2::Zero()));
  RejectCounters want;
  want.nonfinite = 1;
  want.implausible = 1;
  expectCounters(agent.diagnostics().rejected, want);
  EXPECT_EQ(agent.diagnostics().commands, 2u);
  EXPECT_EQ(cb.seq, ca.seq + 1);
}

}  // namespace
}  // namespace swa::agent

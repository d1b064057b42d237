// One commander per UAV (swa/dds/command_gate.h): the first writer heard owns a UAV's cmd_vel, another writer is
// refused while the owner is active and takes over once the owner has been silent for the handover time or its
// participant left.

#include <gtest/gtest.h>

#include "swa/dds/command_gate.h"

namespace swa::dds {
namespace {

using Clock = CommandGate::Clock;
using std::chrono::milliseconds;

WriterId writer(std::uint8_t b) {
  WriterId w{};
  w.fill(b);
  return w;
}

class CommandGateTest : public ::testing::Test {
 protected:
  CommandGate gate{3, milliseconds(500)};
  Clock::time_point t0{};
};

TEST_F(CommandGateTest, FirstWriterOwnsTheUavAndASecondIsRefusedWhileTheFirstTalks) {
  EXPECT_EQ(gate.admit(0, writer(1), t0), Admission::kHandover);
  for (int k = 1; k <= 100; ++k) {
    // The agent at 100 Hz, a rogue in between
    EXPECT_EQ(gate.admit(0, writer(1), t0 + milliseconds(10 * k)), Admission::kOwner);
    EXPECT_EQ(gate.admit(0, writer(2), t0 + milliseconds(10 * k + 5)), Admission::kRefused);
  }
  EXPECT_EQ(gate.refused(), 100u);
  EXPECT_EQ(gate.handovers(), 0u);
  // Another UAV is independent
  EXPECT_EQ(gate.admit(1, writer(2), t0), Admission::kHandover);
}

TEST_F(CommandGateTest, AWriterTakesOverOnlyAfterTheOwnerFellSilent) {
  gate.admit(0, writer(1), t0);
  // The owner crashes; its restarted successor is refused until the owner has been silent for 500 ms
  EXPECT_EQ(gate.admit(0, writer(2), t0 + milliseconds(499)), Admission::kRefused);
  EXPECT_EQ(gate.admit(0, writer(2), t0 + milliseconds(500)), Admission::kHandover);
  EXPECT_EQ(gate.handovers(), 1u);
  // ... and from then on the old writer is the foreign one
  EXPECT_EQ(gate.admit(0, writer(1), t0 + milliseconds(510)), Admission::kRefused);
  EXPECT_EQ(gate.admit(0, writer(2), t0 + milliseconds(520)), Admission::kOwner);
}

TEST_F(CommandGateTest, AWriterTakesOverAtOnceWhenTheOwnersParticipantLeft) {
  // Writers 1 and 2 of one participant (prefix 0x01...), writer 3 of another
  WriterId mixed = writer(3);
  std::fill(mixed.begin(), mixed.begin() + 12, std::uint8_t{1});
  gate.admit(0, writer(1), t0);
  gate.admit(1, writer(1), t0);
  std::array<std::uint8_t, 12> other{};
  other.fill(7);
  gate.participantGone(other);  // someone else's goodbye changes nothing
  EXPECT_EQ(gate.admit(0, writer(2), t0 + milliseconds(10)), Admission::kRefused);
  // The agent re-created its participant: the old one said goodbye, its new writer owns the UAV without waiting
  std::array<std::uint8_t, 12> prefix{};
  prefix.fill(1);
  gate.participantGone(prefix);
  EXPECT_EQ(gate.admit(0, writer(2), t0 + milliseconds(20)), Admission::kHandover);
  EXPECT_EQ(gate.handovers(), 1u);
  EXPECT_EQ(gate.admit(0, writer(1), t0 + milliseconds(30)), Admission::kRefused);
  // A participant back after its lease with the same writer, before anyone else spoke, owns its UAV again
  EXPECT_EQ(gate.admit(1, writer(1), t0 + milliseconds(40)), Admission::kOwner);
  EXPECT_EQ(gate.admit(1, mixed, t0 + milliseconds(50)), Admission::kRefused);
}

TEST_F(CommandGateTest, LateDeliveredOwnerSamplesDoNotMoveItsLastHeardBack) {
  gate.admit(0, writer(1), t0 + milliseconds(400));
  gate.admit(0, writer(1), t0 + milliseconds(100));  // received earlier, drained later
  EXPECT_EQ(gate.admit(0, writer(2), t0 + milliseconds(800)), Admission::kRefused);
}

TEST_F(CommandGateTest, AStallOfTheSimulatorIsNotSilenceOfTheOwner) {
  gate.admit(0, writer(1), t0);
  // The simulator itself did not run for 5 s: the first sample drained afterwards is the rogue's
  gate.shift(std::chrono::seconds(5), t0 + milliseconds(5050));
  EXPECT_EQ(gate.admit(0, writer(2), t0 + milliseconds(5100)), Admission::kRefused);
  EXPECT_EQ(gate.admit(0, writer(1), t0 + milliseconds(5105)), Admission::kOwner);
}

TEST_F(CommandGateTest, AStallNoticedLateDoesNotPushTheOwnerIntoTheFuture) {
  // The owner's sample of the resumed simulator was drained at 5.0 s, the stall of 4.75 s noticed only at 5.01 s
  gate.admit(0, writer(1), t0 + milliseconds(5000));
  gate.shift(milliseconds(4750), t0 + milliseconds(5010));
  // The owner then falls silent (its agent re-created its participant): its successor takes over 0.5 s later, not
  // 0.5 s after 9.75 s
  EXPECT_EQ(gate.admit(0, writer(2), t0 + milliseconds(5600)), Admission::kHandover);
}

// Seen in CI (lockstep, a simulator stopped beyond the DDS lease): an agent re-created its participant and its new
// writer's answer arrived before the old participant's goodbye was processed. It was refused, the step waited for an
// answer that never came again, and the agent was declared dead 2 s later.
TEST_F(CommandGateTest, ACommandRefusedJustBeforeItsOwnersParticipantLeftIsReleased) {
  gate.admit(0, writer(1), t0);
  const auto refused_at = t0 + milliseconds(10);
  EXPECT_EQ(gate.admit(0, writer(2), refused_at), Admission::kRefused);
  EXPECT_EQ(gate.heldCommand(0, writer(2), refused_at, t0 + milliseconds(11)), Held::kKeep) << "the owner is active";
  std::array<std::uint8_t, 12> prefix{};
  prefix.fill(1);
  gate.participantGone(prefix);
  EXPECT_EQ(gate.heldCommand(0, writer(2), refused_at, t0 + milliseconds(12)), Held::kRelease);
  EXPECT_EQ(gate.admit(0, writer(2), t0 + milliseconds(12)), Admission::kHandover);
}

TEST_F(CommandGateTest, ARefusedCommandIsReleasedWhenTheOwnerFallsSilentNeverWhileItTalksAndDroppedWhenStale) {
  gate.admit(0, writer(1), t0);
  // Refused 100 ms after the owner's last command; the owner is silent from then on
  const auto refused_at = t0 + milliseconds(100);
  gate.admit(0, writer(2), refused_at);
  EXPECT_EQ(gate.heldCommand(0, writer(2), refused_at, t0 + milliseconds(499)), Held::kKeep);
  EXPECT_EQ(gate.heldCommand(0, writer(2), refused_at, t0 + milliseconds(500)), Held::kRelease);
  // An owner whose steps are slow (lockstep waiting for another agent) but that answers: its fresh answer, admitted
  // first, keeps the refused command held
  gate.admit(1, writer(1), t0);
  gate.admit(1, writer(3), t0 + milliseconds(5));
  gate.admit(1, writer(1), t0 + milliseconds(900));
  EXPECT_EQ(gate.heldCommand(1, writer(3), t0 + milliseconds(5), t0 + milliseconds(901)), Held::kKeep);
  // Twice the handover time old: dropped, even though its writer could take over now
  EXPECT_EQ(gate.heldCommand(1, writer(3), t0 + milliseconds(5), t0 + milliseconds(1500)), Held::kDrop);
  // Another writer took over meanwhile: the refused one stays foreign
  gate.admit(2, writer(1), t0);
  gate.admit(2, writer(2), t0 + milliseconds(100));
  gate.admit(2, writer(3), t0 + milliseconds(700));
  EXPECT_EQ(gate.heldCommand(2, writer(2), t0 + milliseconds(100), t0 + milliseconds(701)), Held::kKeep);
}

TEST_F(CommandGateTest, EachRefusedWriterIsReportedOnce) {
  gate.admit(0, writer(1), t0);
  EXPECT_TRUE(gate.firstRefusal(0, writer(2)));
  EXPECT_FALSE(gate.firstRefusal(0, writer(2)));
  EXPECT_TRUE(gate.firstRefusal(1, writer(2)));
  EXPECT_TRUE(gate.firstRefusal(0, writer(3)));
  EXPECT_EQ(gate.refusedWriters(), 3u);
}

TEST_F(CommandGateTest, AFloodOfNewWritersIsBoundedInMemory) {
  gate.admit(0, writer(1), t0);
  std::size_t reported = 0;
  for (int k = 0; k < 5000; ++k) {
    WriterId w{};
    w[0] = static_cast<std::uint8_t>(k & 0xff);
    w[1] = static_cast<std::uint8_t>(k >> 8);
    w[15] = 7;
    EXPECT_EQ(gate.admit(0, w, t0 + milliseconds(1)), Admission::kRefused);
    if (gate.firstRefusal(0, w)) ++reported;
  }
  EXPECT_EQ(gate.refused(), 5000u);
  EXPECT_EQ(reported, 1024u);
  EXPECT_EQ(gate.refusedWriters(), 1024u);
}

TEST_F(CommandGateTest, UnknownUavIsAnError) {
  EXPECT_THROW(gate.admit(3, writer(1), t0), std::out_of_range);
  EXPECT_THROW(gate.admit(-1, writer(1), t0), std::out_of_range);
}

}  // namespace
}  // namespace swa::dds

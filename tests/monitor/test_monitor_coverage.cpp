// Issue #11: a monitor that missed part of the run says so. Before, a monitor restarted by hand 28 s into a run
// reported "0 incomplete steps" and could PASS.

#include <gtest/gtest.h>

#include "swa/run_record/verdict.h"
#include "truth_coverage.h"
#include "verdict_input.h"

namespace swa::monitor_node {
namespace {

using record::judge;
using record::Outcome;
using record::Verdict;
using record::VerdictInput;

constexpr agent::StampNs kMs = 1'000'000;

TEST(TruthCoverage, AWholeRunAt10HzMissesNothing) {
  // GIVEN a monitor that saw truth every 100 ms from 0 to 120 s
  TruthCoverage c;
  for (int k = 0; k <= 1200; ++k) c.add(k * 100 * kMs);
  // THEN it missed nothing
  EXPECT_TRUE(c.missed().empty());
  EXPECT_EQ(c.missedSeconds(), 0.0);
}

TEST(TruthCoverage, ALateStartAndAGapAreMissed) {
  // GIVEN a monitor whose first truth is at 28 s, and which then loses 4 s of truth (samples every 100 ms from 28 s
  // to 50 s and from 54 s to 60 s)
  TruthCoverage c;
  for (int k = 280; k <= 500; ++k) c.add(k * 100 * kMs);
  for (int k = 540; k <= 600; ++k) c.add(k * 100 * kMs);
  // THEN it missed 0-28 s and 50-54 s
  ASSERT_EQ(c.missed().size(), 2u);
  EXPECT_DOUBLE_EQ(c.missed()[0].from_s, 0.0);
  EXPECT_DOUBLE_EQ(c.missed()[0].to_s, 28.0);
  EXPECT_DOUBLE_EQ(c.missed()[1].from_s, 50.0);
  EXPECT_DOUBLE_EQ(c.missed()[1].to_s, 54.0);
  EXPECT_NEAR(c.missedSeconds(), 32.0, 1e-9);
}

TEST(TruthCoverage, GapsUpToASecondAndRepeatsAreNotMissed) {
  // GIVEN a monitor that saw truth at 0 s, exactly 1 s later, once more at that stamp, then an older one, then 0.9 s
  // after the newest
  TruthCoverage c;
  c.add(0);
  c.add(1000 * kMs);  // exactly the allowed gap
  c.add(1000 * kMs);  // repeated: ignored
  c.add(500 * kMs);   // older: ignored
  c.add(1900 * kMs);
  // THEN nothing was missed
  EXPECT_TRUE(c.missed().empty());
}

TEST(MonitorVerdict, MissedPartOfTheRunIsIncompleteAndNamed) {
  // GIVEN a completed run that would pass, seen from 28 s on
  VerdictInput in = record::testing::passingRun();
  in.missed = {{0.0, 28.0}};
  // THEN INCOMPLETE, saying what was missed
  const Verdict v = judge(in);
  EXPECT_EQ(v.outcome, Outcome::kIncomplete);
  ASSERT_EQ(v.reasons.size(), 1u);
  EXPECT_EQ(v.reasons[0], "the monitor missed 28 s of the run (0-28 s)");
  // AND without the missed part the same run passes
  in.missed.clear();
  EXPECT_EQ(judge(in).outcome, Outcome::kPass);
}

}  // namespace
}  // namespace swa::monitor_node

// swa_replay --check's verdict line: a recording that lacks commands is not a run whose commands differ.

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "replay_check.h"

namespace swa::replay {
namespace {

UavCheck identicalUav(int uav) {
  UavCheck c;
  c.uav = uav;
  c.inputs = 363;
  c.replayed = 301;
  c.recorded = 301;
  c.identical = 301;
  return c;
}

std::string verdictOf(const std::vector<UavCheck>& checks) {
  const std::string text = formatChecks(checks);
  const std::size_t last = text.rfind('\n', text.size() - 2);
  return text.substr(last == std::string::npos ? 0 : last + 1);
}

TEST(ReplayVerdict, IdenticalOnlyWhenEveryCommandIsRecordedAndEqual) {
  EXPECT_EQ(verdictOf({identicalUav(0), identicalUav(1)}).rfind("IDENTICAL", 0), 0u);
  EXPECT_EQ(verdictOf({}).rfind("DIFFERENT", 0), 0u);  // nothing checked is nothing proven
}

TEST(ReplayVerdict, CommandsMissingFromTheRecordingMakeAnIncompleteRecordingNotADifference) {
  UavCheck gap = identicalUav(3);
  gap.recorded = 287;
  gap.identical = 287;
  gap.not_recorded = 14;
  gap.first_not_recorded_ns = 1'920'000'000;
  const std::string text = formatChecks({identicalUav(0), gap});
  EXPECT_NE(text.find("first command missing from the recording at 1.920 s"), std::string::npos) << text;
  EXPECT_EQ(verdictOf({identicalUav(0), gap})
                .rfind("INCOMPLETE RECORDING: every recorded command replayed bit for "
                       "bit, but 14 replayed command(s) are not in the recording",
                       0),
            0u)
      << text;
}

TEST(ReplayVerdict, AnyDifferenceOrUnreplayedCommandIsDifferentEvenBesideAGap) {
  UavCheck gap = identicalUav(1);
  gap.not_recorded = 2;
  UavCheck differs = identicalUav(2);
  differs.identical = 300;
  differs.differing = 1;
  UavCheck unreplayed = identicalUav(3);
  unreplayed.not_replayed = 1;
  EXPECT_EQ(verdictOf({gap, differs}).rfind("DIFFERENT", 0), 0u);
  EXPECT_EQ(verdictOf({gap, unreplayed}).rfind("DIFFERENT", 0), 0u);
  UavCheck silent = identicalUav(4);  // a UAV whose core answered nothing proves nothing
  silent.replayed = 0;
  silent.identical = 0;
  silent.recorded = 0;
  EXPECT_EQ(verdictOf({gap, silent}).rfind("DIFFERENT", 0), 0u);
}

}  // namespace
}  // namespace swa::replay

// swa_launch --record[=all|monitor]: the spellings, the default set, and the error for an unknown set.

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "error_text.h"
#include "launch_options.h"

namespace swa::launch {
namespace {

std::string recordOptionsError(const std::vector<std::string>& args) {
  return testing::invalidArgumentText([&] { parseLaunchOptions(args); });
}

TEST(LaunchRecordOptions, BareRecordIsCompleteAndEqualsNamesTheSet) {
  // WHEN no --record THEN no recording
  EXPECT_FALSE(parseLaunchOptions({"--scenario", "s"}).record);
  // WHEN --record bare, before another option THEN a complete recording, and the next option is still read
  const LaunchOptions bare = parseLaunchOptions({"--scenario", "s", "--record", "--live", "0"});
  EXPECT_TRUE(bare.record);
  EXPECT_TRUE(bare.record_set == recording::RecordSet::kAll);
  EXPECT_EQ(bare.live, "0");
  // WHEN --record=monitor or --record=all THEN that set
  const LaunchOptions monitor = parseLaunchOptions({"--scenario", "s", "--record=monitor"});
  EXPECT_TRUE(monitor.record);
  EXPECT_TRUE(monitor.record_set == recording::RecordSet::kMonitor);
  EXPECT_TRUE(parseLaunchOptions({"--scenario", "s", "--record=all"}).record_set == recording::RecordSet::kAll);
  // WHEN the set is unknown THEN exit-2 error naming the valid sets
  EXPECT_EQ(recordOptionsError({"--scenario", "s", "--record=sensors"}),
            "--record must be all or monitor, got 'sensors'");
  // WHEN the set is a separate argument THEN it is not taken as the set (it would be the scenario's neighbour)
  EXPECT_EQ(recordOptionsError({"--scenario", "s", "--record", "monitor"}), "unknown argument 'monitor' (see --help)");
  // AND --help shows the syntax and both sets
  const std::string help = launchUsage();
  EXPECT_NE(help.find("--record[=all|monitor]"), std::string::npos) << help;
  EXPECT_NE(help.find("--record=monitor: only truth, events"), std::string::npos) << help;
}

}  // namespace
}  // namespace swa::launch

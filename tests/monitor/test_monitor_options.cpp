// swa_monitor's command line: defaults, every option in both spellings, the --combine list, and every error
// (reported together, never the first one only).

#include <gtest/gtest.h>

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

#include "error_text.h"
#include "monitor_options.h"

namespace swa::monitor_node {
namespace {

// The message of the std::invalid_argument parsing throws ("" when it does not throw).
std::string optionsError(const std::vector<std::string>& args) {
  return testing::invalidArgumentText([&] { parseMonitorOptions(args); });
}

bool contains(const std::string& text, const std::string& what) { return text.find(what) != std::string::npos; }

TEST(MonitorOptions, DefaultsWithoutArguments) {
  // WHEN swa_monitor gets no argument
  const MonitorOptions o = parseMonitorOptions({});
  // THEN it runs live with the documented defaults: out/monitor, no scenario, label, domain or restart log, no
  // timeout, a 5 % band, not quiet
  EXPECT_EQ(o.out_dir, "out/monitor");
  EXPECT_FALSE(o.out_given);
  EXPECT_TRUE(o.scenario_path.empty());
  EXPECT_TRUE(o.overrides.empty());
  EXPECT_TRUE(o.label.empty());
  EXPECT_FALSE(o.domain.has_value());
  EXPECT_TRUE(o.restarts_path.empty());
  EXPECT_DOUBLE_EQ(o.timeout_s, 0.0);
  EXPECT_DOUBLE_EQ(o.tolerance, 0.05);  // issue #10: d_NB within ±5 % of r
  EXPECT_FALSE(o.tolerance_given);
  EXPECT_FALSE(o.quiet);
  EXPECT_FALSE(o.combineMode());
  EXPECT_FALSE(o.help);
}

TEST(MonitorOptions, EveryLiveOptionInBothSpellings) {
  // WHEN every live-mode option is given, some as `--opt value`, some as `--opt=value`, --set twice
  const MonitorOptions o = parseMonitorOptions({"--out", "/tmp/x", "--scenario=s.yaml", "--set", "duration_s=30",
                                                "--set=seed=7", "--label", "swa run", "--domain=77", "--restarts",
                                                "r.csv", "--timeout-s=12.5", "--tolerance", "0.05", "--quiet"});
  // THEN each is read, and the run is live
  EXPECT_EQ(o.out_dir, "/tmp/x");
  EXPECT_TRUE(o.out_given);
  EXPECT_EQ(o.scenario_path, "s.yaml");
  EXPECT_EQ(o.overrides, (std::vector<std::string>{"duration_s=30", "seed=7"}));
  EXPECT_EQ(o.label, "swa run");
  ASSERT_TRUE(o.domain.has_value());
  EXPECT_EQ(*o.domain, "77");  // validated later by resolveDomain (it also reads SWA_DOMAIN)
  EXPECT_EQ(o.restarts_path, "r.csv");
  EXPECT_DOUBLE_EQ(o.timeout_s, 12.5);
  EXPECT_DOUBLE_EQ(o.tolerance, 0.05);
  EXPECT_TRUE(o.tolerance_given);
  EXPECT_TRUE(o.quiet);
  EXPECT_FALSE(o.combineMode());
}

TEST(MonitorOptions, HelpWinsOverProblems) {
  // WHEN --help or -h is given, even beside an unknown option, THEN help is asked for
  EXPECT_TRUE(parseMonitorOptions({"--help"}).help);
  EXPECT_TRUE(parseMonitorOptions({"-h", "--bogus"}).help);
}

TEST(MonitorOptions, CombineListAfterOneFlagAndRepeatedFlags) {
  // WHEN --combine is followed by two LABEL=DIR arguments and then another option
  const MonitorOptions a = parseMonitorOptions({"--combine", "swa=out/a", "standalone=out/b", "--out", "out/c"});
  // THEN both runs are combined, in order
  ASSERT_EQ(a.combine.size(), 2u);
  EXPECT_EQ(a.combine[0].label, "swa");
  EXPECT_EQ(a.combine[0].dir, "out/a");
  EXPECT_EQ(a.combine[1].label, "standalone");
  EXPECT_EQ(a.combine[1].dir, "out/b");
  EXPECT_TRUE(a.combineMode());

  // WHEN --combine is repeated, in both spellings, among other options
  const MonitorOptions b =
      parseMonitorOptions({"--combine=x=d1", "--out=o", "--combine", "y=d=2", "--scenario", "s.yaml", "--set", "k=v"});
  // THEN each gives one run, and only the first '=' separates the label from the directory
  ASSERT_EQ(b.combine.size(), 2u);
  EXPECT_EQ(b.combine[0].label, "x");
  EXPECT_EQ(b.combine[1].dir, "d=2");  // only the first '=' separates
  EXPECT_EQ(b.scenario_path, "s.yaml");
}

TEST(MonitorOptions, BareArgumentOutsideCombineIsUnknown) {
  // WHEN a LABEL=DIR argument comes without --combine THEN it is an unknown argument
  EXPECT_TRUE(contains(optionsError({"swa=out/a"}), "unknown argument 'swa=out/a'"));
  // WHEN it comes after the option that ends the --combine list THEN it is unknown too
  EXPECT_TRUE(contains(optionsError({"--combine", "a=b", "--out", "o", "c=d"}), "unknown argument 'c=d'"));
}

TEST(MonitorOptions, EachErrorIsReported) {
  // WHEN an option is unknown, lacks its value, or its value is empty or out of range THEN the error names it
  EXPECT_TRUE(contains(optionsError({"--frobnicate"}), "unknown option '--frobnicate'"));
  EXPECT_TRUE(contains(optionsError({"--out"}), "--out needs a value"));
  EXPECT_TRUE(contains(optionsError({"--out="}), "--out needs a file name"));
  EXPECT_TRUE(contains(optionsError({"--scenario="}), "--scenario needs a file name"));
  EXPECT_TRUE(contains(optionsError({"--restarts", ""}), "--restarts needs a file name"));
  EXPECT_TRUE(contains(optionsError({"--label="}), "--label needs a name"));
  EXPECT_TRUE(contains(optionsError({"--set", "a=b"}), "--set needs --scenario"));
  EXPECT_TRUE(contains(optionsError({"--timeout-s", "-1"}), "--timeout-s '-1' is not a wall time"));
  EXPECT_TRUE(contains(optionsError({"--timeout-s", "nan"}), "--timeout-s 'nan'"));
  EXPECT_TRUE(contains(optionsError({"--timeout-s", "5s"}), "--timeout-s '5s'"));
  EXPECT_TRUE(contains(optionsError({"--tolerance", "0"}), "--tolerance must be > 0"));
  EXPECT_TRUE(contains(optionsError({"--tolerance", "1.5"}), "--tolerance '1.5' is not a fraction"));
  // WHEN a --combine list is missing, malformed, without --out or with a label twice THEN the error names it
  EXPECT_TRUE(contains(optionsError({"--combine"}), "--combine needs a value"));
  EXPECT_TRUE(contains(optionsError({"--combine", "nolabel", "--out", "o"}), "--combine 'nolabel' is not LABEL=DIR"));
  EXPECT_TRUE(contains(optionsError({"--combine", "=dir", "--out", "o"}), "--combine '=dir' is not LABEL=DIR"));
  EXPECT_TRUE(contains(optionsError({"--combine", "a=", "--out", "o"}), "--combine 'a=' is not LABEL=DIR"));
  EXPECT_TRUE(contains(optionsError({"--combine", "a=x"}), "--combine needs --out DIR"));
  EXPECT_TRUE(contains(optionsError({"--combine", "a=x", "a=y", "--out", "o"}), "label 'a' given twice"));
  // WHEN a live-mode option is given with --combine THEN the error says it applies to the live mode only
  for (const char* live : {"--label", "--domain", "--restarts", "--timeout-s"}) {
    const std::string e = optionsError({"--combine", "a=x", "--out", "o", live, "1"});
    EXPECT_TRUE(contains(e, std::string(live) + " applies to the live mode only")) << e;
  }
}

TEST(MonitorOptions, AllProblemsTogetherOnePerLine) {
  // WHEN four arguments are wrong at once
  const std::string e = optionsError({"--bogus", "--timeout-s", "x", "--set", "a=b", "--tolerance", "2"});
  // THEN the error names each of them, one per line
  EXPECT_TRUE(contains(e, "unknown option '--bogus'"));
  EXPECT_TRUE(contains(e, "--timeout-s 'x'"));
  EXPECT_TRUE(contains(e, "--tolerance '2'"));
  EXPECT_TRUE(contains(e, "--set needs --scenario"));
  EXPECT_EQ(std::count(e.begin(), e.end(), '\n'), 3);
}

TEST(MonitorOptions, UsageDocumentsTheContract) {
  // WHEN the usage text is printed
  const std::string u = monitorUsage();
  // THEN it documents every option, the run directory's files, the restart log's columns and the exit statuses
  for (const char* must : {"--out DIR",
                           "--scenario FILE",
                           "--set key=value",
                           "--label NAME",
                           "--domain D",
                           "--restarts FILE",
                           "--timeout-s S",
                           "--tolerance F",
                           "--quiet",
                           "--combine LABEL=DIR",
                           "wall_s,uav,exit_status,restart_count,backoff_s",
                           "summary.json",
                           "timeseries.csv",
                           "trajectories.csv",
                           "events.csv",
                           "report.html",
                           "0 PASS",
                           "1 FAIL",
                           "3 INCOMPLETE",
                           "2 bad arguments",
                           "SWA_DOMAIN"}) {
    EXPECT_TRUE(contains(u, must)) << must;
  }
}

TEST(MonitorOptions, RecordSetChoosesWhatTheRecordingHolds) {
  // WHEN --record is given without --record-set THEN the recording is complete
  EXPECT_TRUE(parseMonitorOptions({"--record", "r.mcap"}).record_set == recording::RecordSet::kAll);
  EXPECT_TRUE(parseMonitorOptions({}).record_set == recording::RecordSet::kAll);
  // WHEN --record-set monitor (either spelling) THEN only the monitor's topics, all names it back
  EXPECT_TRUE(parseMonitorOptions({"--record", "r.mcap", "--record-set", "monitor"}).record_set ==
              recording::RecordSet::kMonitor);
  EXPECT_TRUE(parseMonitorOptions({"--record-set=monitor", "--record=r.mcap"}).record_set ==
              recording::RecordSet::kMonitor);
  EXPECT_TRUE(parseMonitorOptions({"--record", "r.mcap", "--record-set", "all"}).record_set ==
              recording::RecordSet::kAll);
  // WHEN the set is unknown THEN the error lists the valid ones
  EXPECT_EQ(optionsError({"--record", "r.mcap", "--record-set", "sensors"}),
            "--record-set must be all or monitor, got 'sensors'");
  // WHEN --record-set comes without --record THEN it says what it needs
  EXPECT_EQ(optionsError({"--record-set", "monitor"}),
            "--record-set needs --record FILE.mcap (it says what the recording holds)");
  // WHEN it is given with --combine THEN it is a live-mode option
  const std::string e = optionsError({"--combine", "a=x", "--out", "o", "--record-set", "monitor"});
  EXPECT_TRUE(contains(e, "--record-set applies to the live mode only")) << e;
  EXPECT_FALSE(contains(e, "needs --record")) << e;
  // AND --help names both sets
  const std::string help = monitorUsage();
  EXPECT_TRUE(contains(help, "--record-set SET")) << help;
  EXPECT_TRUE(contains(help, "one of all or monitor")) << help;
}

}  // namespace
}  // namespace swa::monitor_node

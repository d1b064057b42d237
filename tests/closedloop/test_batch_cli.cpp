// swa_batch as a user meets it: its options, its exit codes and the files it writes.

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "batch_options.h"
#include "scratch.h"

namespace swa::batch {
namespace {

namespace fs = std::filesystem;

int runBatch(const std::string& args) {
  const std::string cmd = std::string(SWA_BATCH_BINARY) + " " + args + " > /dev/null 2>&1";
  const int status = std::system(cmd.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST(BatchOptions, ParsesEveryOption) {
  const BatchOptions o = parseBatchOptions({"--scenario", "s.yaml", "--set", "uav_count=4", "--set", "agent.k=2",
                                            "--seeds", "12", "--jobs", "2", "--out", "d", "--compare", "standalone"});
  EXPECT_EQ(o.scenario_path, "s.yaml");
  EXPECT_EQ(o.overrides, (std::vector<std::string>{"uav_count=4", "agent.k=2"}));
  EXPECT_EQ(o.seeds, 12);
  EXPECT_EQ(o.jobs, 2);
  EXPECT_EQ(o.out_dir, "d");
  ASSERT_TRUE(o.compare.has_value());
  EXPECT_EQ(*o.compare, agent::Mode::kStandalone);
}

TEST(BatchOptions, ReportsEveryProblemAtOnce) {
  // GIVEN four distinct mistakes
  try {
    parseBatchOptions({"--seeds", "0", "--jobs", "x", "--compare", "maybe", "--frobnicate"});
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    // THEN one error names all of them, plus the missing --scenario
    const std::string m = e.what();
    for (const char* needle : {"--seeds", "--jobs", "--compare", "--frobnicate", "--scenario FILE is required"}) {
      EXPECT_NE(m.find(needle), std::string::npos) << needle << " missing from: " << m;
    }
  }
}

TEST(BatchCli, MalformedScenarioExitsWith2AndWritesNothing) {
  const swa::testing::ScratchDir scratch("swa_batch_bad");
  const fs::path out = scratch / "out";
  const std::string scenario = std::string(SWA_SOURCE_DIR) + "/deploy/scenarios/dropout_4.yaml";
  EXPECT_EQ(runBatch("--scenario " + scenario + " --set uav_count=-3 --set agent.kk=2 --out " + out.string()), 2);
  EXPECT_EQ(runBatch("--scenario /nonexistent.yaml --out " + out.string()), 2);
  EXPECT_EQ(runBatch("--bogus"), 2);
  EXPECT_FALSE(fs::exists(out));
  EXPECT_EQ(runBatch("--help"), 0);
}

TEST(BatchCli, UnwritableOutputExits2BeforeRunning) {
  // GIVEN --out where nothing can be created (issue #11: every seed ran, then it failed to write, exit 1)
  const std::string scenario = std::string(SWA_SOURCE_DIR) + "/deploy/scenarios/dropout_4.yaml";
  // THEN a usage error, exit 2
  EXPECT_EQ(runBatch("--scenario " + scenario + " --set duration_s=600 --seeds 20 --out /proc/swa_nope"), 2);
}

TEST(BatchCli, ShortRunWritesSummaryAndSeries) {
  // GIVEN a 5 s run of 2 seeds with the standalone comparison
  const swa::testing::ScratchDir scratch("swa_batch_ok");
  const fs::path out = scratch / "out";
  const std::string scenario = std::string(SWA_SOURCE_DIR) + "/deploy/scenarios/dropout_4.yaml";
  ASSERT_EQ(runBatch("--scenario " + scenario + " --set duration_s=5 --seeds 2 --jobs 2 --compare standalone --out " +
                     out.string()),
            0);
  // THEN summary.json has both modes, both seeds and the keys, and each seed has its CSV
  std::ifstream in(out / "summary.json");
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string json = ss.str();
  for (const char* key :
       {"\"mean_neighbor_distance_m\"", "\"min_separation_m\"", "\"collisions\"", "\"drift_velocity_mps\"",
        "\"uav_displacement_m\"", "\"groups\"", "\"anees_position\"", "\"aggregate\"", "\"mode\": \"swa\"",
        "\"mode\": \"standalone\"", "\"seed\": 1", "\"seed\": 2"}) {
    EXPECT_NE(json.find(key), std::string::npos) << key;
  }
  for (const char* mode : {"swa", "standalone"}) {
    for (const char* file : {"seed_1.csv", "seed_2.csv", "seed_1_events.csv", "seed_2_events.csv"}) {
      EXPECT_TRUE(fs::exists(out / mode / file)) << mode << file;
    }
  }
  EXPECT_TRUE(fs::exists(out / "scenario.yaml"));
  EXPECT_TRUE(fs::exists(out / "report" / "report.html"));
}

}  // namespace
}  // namespace swa::batch

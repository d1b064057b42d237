// A study in a scenario file (deploy/programs/study/study_section.h): the `study:` section read in both spellings,
// every mistake in it reported, the command line on top of it, and the scenario loader skipping it (but nothing else).

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "scratch.h"
#include "study_section.h"
#include "swa/params/error.h"
#include "swa/sim/scenario_io.h"

namespace swa::study {
namespace {

// One scenario file per test, removed afterwards.
class StudySectionTest : public ::testing::Test {
 protected:
  std::string write(const std::string& text) { return dir_.write("study.yaml", text).string(); }

  // The problems a section raises, one per line.
  std::string problems(const std::string& text) {
    try {
      readStudySection(write(text));
    } catch (const params::ConfigError& e) {
      return e.what();
    }
    return "";
  }

 private:
  swa::testing::ScratchDir dir_{"swa_test_study_section"};
};

const char* const kStudy = R"(uav_count: 8
duration_s: 30
study:
  seeds: 20
  sweep:
    uav_count: [4, 8, 16]
    agent:
      formation:
        neighbourhood: [gabriel, k_nearest]
    imu.bias_std: 0.15
)";

TEST_F(StudySectionTest, ReadsSeedsAndAxesInFileOrderNestedOrDotted) {
  const StudySection s = readStudySection(write(kStudy));
  ASSERT_TRUE(s.present);
  EXPECT_EQ(s.seeds, 20);
  ASSERT_EQ(s.axes.size(), 3u);
  EXPECT_EQ(s.axes[0].key, "uav_count");
  EXPECT_EQ(s.axes[0].values, (std::vector<std::string>{"4", "8", "16"}));
  EXPECT_EQ(s.axes[1].key, "agent.formation.neighbourhood");
  EXPECT_EQ(s.axes[1].values, (std::vector<std::string>{"gabriel", "k_nearest"}));
  EXPECT_EQ(s.axes[2].key, "imu.bias_std");  // a single value: an axis of one point
  EXPECT_EQ(s.axes[2].values, (std::vector<std::string>{"0.15"}));
}

TEST_F(StudySectionTest, AFileWithoutTheSectionIsNoStudy) {
  const StudySection s = readStudySection(write("uav_count: 8\n"));
  EXPECT_FALSE(s.present);
  EXPECT_TRUE(s.axes.empty());
  EXPECT_EQ(s.seeds, 0);
}

TEST_F(StudySectionTest, EveryMistakeIsReportedWithItsLine) {
  const std::string p = problems(R"(study:
  seeds: 0
  sweeps:
    uav_count: [4, 8]
  sweep:
    uav_count: [4, 4]
    duration_s: []
    mps.range_m: [[40, 50]]
)");
  EXPECT_NE(p.find("study.seeds must be a whole number in [1, 100000], got '0' (line 2"), std::string::npos) << p;
  EXPECT_NE(p.find("unknown entry 'study.sweeps.uav_count' (line 4"), std::string::npos) << p;
  EXPECT_NE(p.find("study.sweep.uav_count (line 6, column 16) gives 4 twice"), std::string::npos) << p;
  EXPECT_NE(p.find("study.sweep.duration_s (line 7, column 17) gives no value"), std::string::npos) << p;
  EXPECT_NE(p.find("'study.sweep.mps.range_m' must list plain values, got a sequence (line 8"), std::string::npos) << p;
  EXPECT_NE(problems("study:\n  seeds: [1, 2]\n  sweep: {uav_count: [4]}\n").find("got a list"), std::string::npos);
  EXPECT_NE(problems("study:\n  seeds: 2.5\n  sweep: {uav_count: [4]}\n").find("got '2.5'"), std::string::npos);
  EXPECT_NE(problems("study: [4, 8]\n").find("'study' must be a map, got a sequence"), std::string::npos);
  EXPECT_NE(problems("study:\n  seeds: 2\n  seeds: 7\n  sweep: {uav_count: [4]}\n").find("study.seeds given twice"),
            std::string::npos);
  EXPECT_NE(problems("study:\n  seeds: 2\nstudy:\n  sweep: {uav_count: [4]}\n").find("'study' given twice"),
            std::string::npos);
  EXPECT_NE(problems("study:\n  sweep: {uav_count: [4]\n").find("invalid YAML"), std::string::npos);
  EXPECT_NE(problems("study:\n  sweep: {uav_count: }\n").find("has no value"), std::string::npos);
}

std::string same(const std::string& key) { return key; }
// As the scenario's aliases (sim::canonicalScenarioKey).
std::string aliases(const std::string& key) { return key == "agent.k" ? "agent.formation.k" : key; }

TEST_F(StudySectionTest, ReadsVariantsNestedOrDottedAndSaysWhatIsWrongWithOne) {
  const StudySection s = readStudySection(write(R"(uav_count: 8
study:
  sweep:
    uav_count: [4, 8]
  variants:
    gabriel:
      agent:
        formation: {neighbourhood: gabriel}
      agent.focal.bias_window_s: 30
    k3: {agent.formation.neighbourhood: k_nearest, agent.formation.k: 3}
)"));
  ASSERT_EQ(s.variants.size(), 2u);
  EXPECT_EQ(s.variants[0].name, "gabriel");
  EXPECT_EQ(s.variants[0].overrides,
            (std::vector<std::string>{"agent.formation.neighbourhood=gabriel", "agent.focal.bias_window_s=30"}));
  EXPECT_EQ(s.variants[1].overrides,
            (std::vector<std::string>{"agent.formation.neighbourhood=k_nearest", "agent.formation.k=3"}));
  EXPECT_NE(problems("study:\n  variants:\n    k3: 3\n").find("a variant is a map"), std::string::npos);
  EXPECT_NE(problems("study:\n  variants:\n    k3: {agent.formation.k: [2, 3]}\n").find("line 3"), std::string::npos);
}

TEST(StudySectionPlan, CommandLineVariantsReplaceTheFilesByNameOrAddAndKeysAreCanonical) {
  StudySection file;
  file.present = true;
  file.axes = {parseSweep("uav_count=4,8")};
  file.variants = {parseVariant("k3:agent.formation.k=3"), parseVariant("k2:agent.formation.k=2")};
  const StudyPlan plan =
      combinePlan(file, {}, {"k3:agent.k=4", "gabriel:agent.formation.neighbourhood=gabriel"}, 0, 1, aliases);
  ASSERT_EQ(plan.variants.size(), 3u);
  EXPECT_EQ(plan.variants[0].overrides, (std::vector<std::string>{"agent.formation.k=4"})) << "replaced, canonical";
  EXPECT_EQ(plan.variants[2].name, "gabriel");
  EXPECT_EQ(plan.axes.back().values, (std::vector<std::string>{"k3", "k2", "gabriel"}));
  EXPECT_THROW(combinePlan(file, {}, {"s:seed=3"}, 0, 1, same), std::invalid_argument);
  EXPECT_THROW(combinePlan(file, {}, {"big:uav_count=16"}, 0, 1, same), std::invalid_argument);
}

TEST(StudySectionPlan, CommandLineReplacesAnAxisInPlaceAddsNewOnesAndOverridesSeeds) {
  StudySection file;
  file.present = true;
  file.seeds = 20;
  file.axes = {parseSweep("uav_count=4,8"), parseSweep("agent.formation.neighbourhood=gabriel,k_nearest")};

  const StudyPlan unchanged = combinePlan(file, {}, {}, 0, 1, same);
  EXPECT_EQ(unchanged.seeds, 20);
  ASSERT_EQ(unchanged.axes.size(), 2u);

  const StudyPlan plan = combinePlan(file, {"imu.bias_std=0.05,0.15", "uav_count=16"}, {}, 3, 1, same);
  EXPECT_EQ(plan.seeds, 3);
  ASSERT_EQ(plan.axes.size(), 3u);
  EXPECT_EQ(plan.axes[0].key, "uav_count");
  EXPECT_EQ(plan.axes[0].values, (std::vector<std::string>{"16"}));
  EXPECT_EQ(plan.axes[1].key, "agent.formation.neighbourhood");
  EXPECT_EQ(plan.axes[2].key, "imu.bias_std");

  EXPECT_EQ(combinePlan(StudySection{}, {"uav_count=4"}, {}, 0, 7, same).seeds, 7)
      << "--seeds' default without a section";
  for (const std::vector<std::string>& bad :
       std::vector<std::vector<std::string>>{{"seed=1,2"}, {"uav_count=4", "uav_count=8"}, {"uav_count"}}) {
    EXPECT_THROW(combinePlan(file, bad, {}, 0, 1, same), std::invalid_argument) << bad.back();
  }
  // A section that sweeps nothing is a study only with the command line's sweeps.
  StudySection seeds_only;
  seeds_only.present = true;
  seeds_only.seeds = 3;
  EXPECT_THROW(combinePlan(seeds_only, {}, {}, 0, 1, same), std::invalid_argument);
  EXPECT_EQ(combinePlan(seeds_only, {"uav_count=4,8"}, {}, 0, 1, same).axes.size(), 1u);

  // Keys by their canonical names: an alias on the command line replaces the file's axis, spaces are not part of a
  // key or value.
  StudySection k_file;
  k_file.present = true;
  k_file.axes = {parseSweep("agent.formation.k=1,5")};
  const StudyPlan k = combinePlan(k_file, {" agent.k = 2 , 3 "}, {}, 0, 1, aliases);
  ASSERT_EQ(k.axes.size(), 1u);
  EXPECT_EQ(k.axes[0].key, "agent.formation.k");
  EXPECT_EQ(k.axes[0].values, (std::vector<std::string>{"2", "3"}));
  EXPECT_THROW(combinePlan(k_file, {"seed =5,9"}, {}, 0, 1, same), std::invalid_argument);

  StudySection seeded = file;
  seeded.axes.push_back(parseSweep("seed=1,2"));
  EXPECT_THROW(combinePlan(seeded, {}, {}, 0, 1, same), std::invalid_argument);
}

TEST_F(StudySectionTest, TheScenarioLoaderSkipsTheSectionButNothingElse) {
  const sim::Scenario s = sim::loadScenario(write(kStudy));
  EXPECT_EQ(s.uav_count, 8) << "the base scenario, not a grid point";
  EXPECT_EQ(s.duration_s, 30.0);
  EXPECT_EQ(sim::scenarioToYaml(s).find("study"), std::string::npos) << "the effective scenario has no study";

  EXPECT_THROW(sim::loadScenario(write("uav_count: 8\nstudies:\n  seeds: 2\n")), params::ConfigError);
  EXPECT_THROW(sim::loadScenario(write("uav_count: 8\nagent:\n  study:\n    seeds: 2\n")), params::ConfigError)
      << "only the top-level section is foreign";
  EXPECT_THROW(sim::loadScenario(write(kStudy), {"study.seeds=3"}), params::ConfigError) << "--set cannot reach it";
}

}  // namespace
}  // namespace swa::study

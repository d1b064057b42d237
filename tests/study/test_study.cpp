// Studies (deploy/programs/study): the grid, its shards, study.json both ways, the merge and its refusals, the tidy
// table.

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "scratch.h"
#include "study_plan.h"
#include "study_record.h"

namespace swa::study {
namespace {

StudyPlan plan2x3(int seeds) {
  StudyPlan p;
  p.axes = {parseSweep("uav_count=4,8"), parseSweep("agent.formation.neighbourhood=gabriel,k_nearest,x")};
  p.seeds = seeds;
  return p;
}

TEST(StudyPlan, SweepsAndShardsParseOrSayWhatIsWrong) {
  const Axis a = parseSweep("uav_count=4,8,16");
  EXPECT_EQ(a.key, "uav_count");
  EXPECT_EQ(a.values, (std::vector<std::string>{"4", "8", "16"}));
  for (const char* bad : {"uav_count", "=4,8", "uav_count=4,,8", "uav_count=4,4", "uav_count="}) {
    EXPECT_THROW(parseSweep(bad), std::invalid_argument) << bad;
  }
  const Shard s = parseShard("2/5");
  EXPECT_EQ(s.index, 2);
  EXPECT_EQ(s.count, 5);
  for (const char* bad : {"0/3", "4/3", "1/0", "a/2", "2", "1/2/3", "-1/2"}) {
    EXPECT_THROW(parseShard(bad), std::invalid_argument) << bad;
  }
  StudyPlan twice;
  twice.axes = {parseSweep("k=1,2"), parseSweep("k=3")};
  EXPECT_EQ(planProblems(twice).size(), 1u);
}

TEST(StudyPlan, GridIsRowMajorWithTheLastAxisFastest) {
  const StudyPlan p = plan2x3(4);
  EXPECT_EQ(pointCount(p), 6u);
  EXPECT_EQ(runCount(p), 24u);
  EXPECT_EQ(pointValues(p, 0), (std::vector<std::string>{"4", "gabriel"}));
  EXPECT_EQ(pointValues(p, 1), (std::vector<std::string>{"4", "k_nearest"}));
  EXPECT_EQ(pointValues(p, 3), (std::vector<std::string>{"8", "gabriel"}));
  EXPECT_EQ(pointOverrides(p, 5), (std::vector<std::string>{"uav_count=8", "agent.formation.neighbourhood=x"}));
}

TEST(StudyPlan, ShardsCoverEveryRunOnceAndSpreadEachPointOverShards) {
  const StudyPlan p = plan2x3(4);
  for (int n : {1, 3, 4, 7, 30}) {
    std::multiset<std::size_t> seen;
    for (int i = 1; i <= n; ++i) {
      for (const RunRef& r : shardRuns(p, {i, n})) {
        seen.insert(r.index);
        EXPECT_EQ(r.index, r.point * 4 + static_cast<std::size_t>(r.seed_offset));
        EXPECT_EQ(r.index % static_cast<std::size_t>(n), static_cast<std::size_t>(i - 1));
      }
    }
    EXPECT_EQ(seen.size(), 24u) << n << " shards";
    EXPECT_EQ(std::set<std::size_t>(seen.begin(), seen.end()).size(), 24u) << n << " shards: a run twice";
  }
}

TEST(StudyPlan, VariantsAreTheLastAxisAndEachPointGetsItsVariantsOverrides) {
  // GIVEN a sweep of two sizes and two variants, each setting two keys
  StudyPlan plan;
  plan.axes = {parseSweep("uav_count=4,8")};
  setVariants(plan, {parseVariant("gabriel:agent.formation.neighbourhood=gabriel, agent.focal.bias_window_s=30"),
                     parseVariant("k3:agent.formation.neighbourhood=k_nearest,agent.formation.k=3")});
  // THEN the variants are one more axis, last (fastest), named by the variants
  ASSERT_EQ(plan.axes.size(), 2u);
  EXPECT_EQ(plan.axes[1].key, kVariantAxis);
  EXPECT_EQ(plan.axes[1].values, (std::vector<std::string>{"gabriel", "k3"}));
  EXPECT_EQ(pointCount(plan), 4u);
  EXPECT_TRUE(planProblems(plan).empty());
  // AND a grid point's overrides are its swept values, then every override of its variant, spaces trimmed
  EXPECT_EQ(pointValues(plan, 1), (std::vector<std::string>{"4", "k3"}));
  EXPECT_EQ(pointOverrides(plan, 1), (std::vector<std::string>{"uav_count=4", "agent.formation.neighbourhood=k_nearest",
                                                               "agent.formation.k=3"}));
  EXPECT_EQ(pointOverrides(plan, 2), (std::vector<std::string>{"uav_count=8", "agent.formation.neighbourhood=gabriel",
                                                               "agent.focal.bias_window_s=30"}));
  // AND a malformed variant says what is wrong
  for (const char* bad : {"k3", ":agent.formation.k=3", "k3:", "k3:agent.formation.k", "k3:=3",
                          "k3:agent.formation.k=3,agent.formation.k=2"}) {
    EXPECT_THROW(parseVariant(bad), std::invalid_argument) << bad;
  }
  // AND a variant that sets a swept key, or a name given twice, is a problem of the plan
  StudyPlan clash = plan;
  setVariants(clash, {parseVariant("big:uav_count=16"), parseVariant("big:agent.formation.k=2")});
  EXPECT_EQ(planProblems(clash).size(), 2u);
  // AND a plan of variants alone is a study
  StudyPlan only;
  setVariants(only, {parseVariant("a:agent.formation.k=2")});
  EXPECT_TRUE(planProblems(only).empty());
}

StudyRecord record(const StudyPlan& plan, Shard shard) {
  StudyRecord s;
  s.version = "test";
  s.scenario = "s.yaml";
  s.scenario_yaml = "uav_count: 4\n";
  s.first_seed = 10;
  s.plan = plan;
  s.shard = shard;
  s.study_id = studyId(s.version, s.scenario_yaml, plan, s.first_seed);
  for (const RunRef& r : shardRuns(plan, shard)) {
    s.runs.push_back({r.index,
                      r.point,
                      s.first_seed + static_cast<std::uint64_t>(r.seed_offset),
                      {{"uav_count", 4.0},
                       {"mean_neighbor_distance_m", 0.1 * static_cast<double>(r.index) + 1e-13},
                       {"anees_position", r.index % 2 ? std::nan("") : 1.0 / 3.0}}});
  }
  return s;
}

TEST(StudyRecord, JsonRoundTripKeepsEveryValueExactly) {
  const StudyRecord s = record(plan2x3(2), {2, 3});
  const StudyRecord back = studyFromJson(studyJson(s), "test");
  EXPECT_EQ(studyJson(back), studyJson(s));
  ASSERT_EQ(back.runs.size(), s.runs.size());
  EXPECT_EQ(back.runs[1].metrics[1].value, s.runs[1].metrics[1].value) << "bit for bit";
  ASSERT_EQ(s.runs[0].index, 1u);  // shard 2/3 starts at run 1, whose ANEES is NaN
  EXPECT_TRUE(std::isnan(back.runs[0].metrics[2].value)) << "NaN written as null comes back NaN";
  EXPECT_EQ(back.runs[1].metrics[2].value, 1.0 / 3.0);
  EXPECT_THROW(studyFromJson(record::Json::object(), "x.json"), StudyError);
}

TEST(StudyRecord, VariantsSurviveTheJsonRoundTripAndChangeTheId) {
  StudyPlan plan = plan2x3(2);
  const std::string without = studyId("v", "yaml", plan, 1);
  setVariants(plan, {parseVariant("k3:agent.formation.k=3")});
  const StudyRecord s = record(plan, {1, 1});
  const StudyRecord back = studyFromJson(studyJson(s), "test");
  ASSERT_EQ(back.plan.variants.size(), 1u);
  EXPECT_EQ(back.plan.variants[0].name, "k3");
  EXPECT_EQ(back.plan.variants[0].overrides, (std::vector<std::string>{"agent.formation.k=3"}));
  EXPECT_EQ(studyJson(back), studyJson(s));
  EXPECT_NE(studyId("v", "yaml", plan, 1), without);
  // A study without variants writes no "variants" member: its id and files are what they were before variants.
  EXPECT_FALSE(studyJson(record(plan2x3(2), {1, 1}))["plan"].contains("variants"));
}

TEST(StudyRecord, ShardsMergeIntoTheWholeStudyAndNothingElse) {
  const StudyPlan p = plan2x3(2);
  const StudyRecord whole = record(p, {1, 1});
  std::vector<StudyRecord> shards = {record(p, {3, 3}), record(p, {1, 3}), record(p, {2, 3})};
  const StudyRecord merged = mergeShards(shards);
  EXPECT_EQ(studyJson(merged), studyJson(whole));
  EXPECT_EQ(tidyCsv(merged), tidyCsv(whole));
  for (std::size_t point = 0; point < pointCount(p); ++point) {
    // As text: the files are compared byte for byte (and an aggregate's NaN is null there, unequal to itself here).
    EXPECT_EQ(pointSummaryJson(merged, point).dump(), pointSummaryJson(whole, point).dump());
  }

  const auto refuses = [](std::vector<StudyRecord> given, const std::string& why) {
    try {
      mergeShards(given);
      ADD_FAILURE() << "merged although " << why;
    } catch (const StudyError& e) {
      EXPECT_NE(std::string(e.what()).find(why), std::string::npos) << e.what();
    }
  };
  refuses({shards[0], shards[1]}, "2/3 not given");
  refuses({shards[0], shards[1], shards[2], shards[1]}, "repeats run");
  StudyRecord other = shards[2];
  other.study_id = "0123";
  refuses({shards[0], shards[1], other}, "is of study 0123");
  StudyRecord newer = shards[2];
  newer.version = "later";
  refuses({shards[0], shards[1], newer}, "was run by later");
}

TEST(StudyRecord, StudyIdChangesWithEverythingThatMakesTheResults) {
  const StudyPlan p = plan2x3(2);
  const std::string id = studyId("v", "yaml", p, 1);
  EXPECT_EQ(id, studyId("v", "yaml", p, 1));
  EXPECT_NE(id, studyId("w", "yaml", p, 1));
  EXPECT_NE(id, studyId("v", "yaml2", p, 1));
  EXPECT_NE(id, studyId("v", "yaml", p, 2));
  EXPECT_NE(id, studyId("v", "yaml", plan2x3(3), 1));
}

TEST(StudyRecord, TidyTableHasOneRowPerRunAndEachColumnOnce) {
  const StudyRecord s = record(plan2x3(2), {1, 1});
  const std::string csv = tidyCsv(s);
  const std::string header = csv.substr(0, csv.find('\n'));
  EXPECT_EQ(header, "uav_count,agent.formation.neighbourhood,seed,mean_neighbor_distance_m,anees_position")
      << "the metric uav_count is the swept column";
  EXPECT_EQ(static_cast<std::size_t>(std::count(csv.begin(), csv.end(), '\n')), 1 + s.runs.size());
  EXPECT_NE(csv.find("\n4,gabriel,10,1e-13,0.3333333333333333\n"), std::string::npos) << csv;
  EXPECT_NE(csv.find(",nan\n"), std::string::npos) << "NaN as pandas reads it";
}

TEST(StudyRecord, WrittenAndReadBackFromADirectory) {
  const swa::testing::ScratchDir scratch("swa_test_study");
  const std::filesystem::path dir = scratch / "study";
  const StudyRecord s = record(plan2x3(1), {1, 1});
  writeStudy(dir.string(), s);
  EXPECT_TRUE(std::filesystem::exists(dir / "runs.csv"));
  EXPECT_TRUE(std::filesystem::exists(dir / "points" / "5" / "summary.json"));
  EXPECT_EQ(studyJson(readStudy(dir.string())), studyJson(s));
  EXPECT_THROW(readStudy((dir / "points").string()), StudyError);
}

}  // namespace
}  // namespace swa::study

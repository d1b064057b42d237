// summary.json's metric members (swa/run_record/run_dir.h): swa_batch's per-seed entries and its aggregate, written
// through nlohmann::json. Every summary field is a member exactly once; what is not finite is null (JSON has no NaN).

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "markup_support.h"
#include "swa/run_record/run_dir.h"

namespace swa::record {
namespace {

using monitor::testing::occurrences;

TEST(RecordJson, SummaryHasEveryKeyOnceAndNullForMissingValues) {
  // GIVEN a summary with some values and the rest left NaN
  monitor::Summary s;
  s.steps = 12;
  s.mean_neighbor_distance_m = 9.75;
  s.collisions = 3;
  s.groups = 1;
  // WHEN it is written
  const std::string json = jsonText(metricsJson(s));
  // THEN every field the brief requires is a member, exactly once
  for (const char* key :
       {"mean_neighbor_distance_m", "min_separation_m", "collisions", "drift_velocity_mps", "uav_displacement_m",
        "groups", "spread_m", "formation_error_m", "anees_position", "anees_velocity", "anees_band_low",
        "anees_band_high", "anees_agents", "nees_skipped_unknown_id", "edge_length_m", "drift_velocity_windows_mps"}) {
    EXPECT_EQ(occurrences(json, std::string("\"") + key + "\":"), 1) << key;
  }
  // AND so is every field of the flat view, with its value, null where it is not finite
  const Json parsed = Json::parse(json);
  const std::vector<monitor::NamedValue> fields = monitor::summaryFields(s);
  EXPECT_EQ(fields.size(), 33u);
  EXPECT_EQ(parsed.size(), fields.size());
  for (const monitor::NamedValue& f : fields) {
    ASSERT_TRUE(parsed.contains(f.key)) << f.key;
    if (std::isfinite(f.value)) {
      EXPECT_EQ(parsed[f.key].get<double>(), f.value) << f.key;
    } else {
      EXPECT_TRUE(parsed[f.key].is_null()) << f.key;
    }
  }
  EXPECT_EQ(parsed["mean_neighbor_distance_m"].get<double>(), 9.75);
  EXPECT_EQ(parsed["collisions"].get<double>(), 3.0);
  EXPECT_TRUE(parsed["anees_position"].is_null());
  EXPECT_EQ(json.front(), '{');
  EXPECT_EQ(json.find("nan"), std::string::npos);
}

TEST(RecordJson, AggregateListsEveryKeyWithItsStatistics) {
  // GIVEN two runs, one key in both, one finite in neither
  const std::vector<std::vector<monitor::NamedValue>> runs{{{"d_nb", 1.0}, {"gone", std::nan("")}}, {{"d_nb", 3.0}}};
  // WHEN the aggregate is written and read back
  const Json j = Json::parse(jsonText(aggregateJson(monitor::aggregate(runs))));
  // THEN it has the count and each key's statistics, in order, null where there is no value
  EXPECT_EQ(j["runs"].get<int>(), 2);
  ASSERT_EQ(j["metrics"].size(), 2u);
  EXPECT_EQ(j["metrics"].begin().key(), "d_nb");
  const Json& d = j["metrics"]["d_nb"];
  EXPECT_EQ(d["runs"].get<int>(), 2);
  EXPECT_EQ(d["mean"].get<double>(), 2.0);
  EXPECT_EQ(d["std"].get<double>(), 1.4142135623730951);
  EXPECT_EQ(d["min"].get<double>(), 1.0);
  EXPECT_EQ(d["max"].get<double>(), 3.0);
  const Json& gone = j["metrics"]["gone"];
  EXPECT_EQ(gone["runs"].get<int>(), 0);
  for (const char* stat : {"mean", "std", "min", "max"}) EXPECT_TRUE(gone[stat].is_null()) << stat;
  // AND a key needing escapes cannot break the document, and no run is an empty aggregate
  const std::string odd =
      jsonText(aggregateJson(monitor::aggregate(std::vector<std::vector<monitor::NamedValue>>{{{"a\"b\\c\n", 1.0}}})));
  EXPECT_TRUE(Json::parse(odd)["metrics"].contains("a\"b\\c\n"));
  const Json none = Json::parse(jsonText(aggregateJson(monitor::aggregate(std::vector<monitor::Summary>{}))));
  EXPECT_EQ(none["runs"].get<int>(), 0);
  EXPECT_TRUE(none["metrics"].empty());
}

}  // namespace
}  // namespace swa::record

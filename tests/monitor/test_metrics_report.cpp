// CSV and JSON formats and the aggregate over seeds.

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "markup_support.h"
#include "swa/monitor/summary_format.h"

namespace swa::monitor {
namespace {

using testing::occurrences;

TEST(MetricsReport, CsvHeaderIsTheDocumentedColumnList) {
  EXPECT_EQ(csvHeader(),
            "t_s,d_nb_m,centroid_x_m,centroid_y_m,drift_mps,min_sep_m,collisions,spread_m,groups,formation_error_m,"
            "nees_pos,nees_vel");
}

TEST(MetricsReport, CsvRowHasOneFieldPerColumnInHeaderOrder) {
  // GIVEN a row with distinct, exactly representable values and no NEES
  TimeSeriesRow row;
  row.t_s = 1.5;
  row.d_nb_m = 10.0;
  row.centroid_x_m = 2.0;
  row.centroid_y_m = -3.0;
  row.drift_mps = 0.25;
  row.min_sep_m = 7.5;
  row.collisions = 2;
  row.spread_m = 11.0;
  row.groups = 1;
  row.formation_error_m = 0.5;
  // WHEN formatted THEN the fields are in header order, integers as integers, a missing value as nan
  EXPECT_EQ(formatCsvRow(row), "1.5,10,2,-3,0.25,7.5,2,11,1,0.5,nan,nan");
  EXPECT_EQ(occurrences(formatCsvRow(row), ","), occurrences(csvHeader(), ","));
}

TEST(MetricsReport, RowIsTakenFromTheStepMetrics) {
  StepMetrics m;
  m.t_s = 3.0;
  m.geometry.mean_neighbor_distance_m = 9.5;
  m.geometry.centroid_m = agent::Vec2(1.0, 2.0);
  m.geometry.min_separation_m = 8.0;
  m.geometry.spread_m = 6.0;
  m.geometry.groups = 2;
  m.geometry.formation_error_m = 0.75;
  m.nees.position = 1.25;
  m.nees.velocity = 0.5;
  m.collisions = 4;
  m.drift_mps = 0.125;
  EXPECT_EQ(formatCsvRow(toRow(m)), "3,9.5,1,2,0.125,8,4,6,2,0.75,1.25,0.5");
}

TEST(MetricsReport, NumbersAreShortestRoundTrip) {
  EXPECT_EQ(formatNumber(0.1), "0.1");
  EXPECT_EQ(formatNumber(-2.0), "-2");
  EXPECT_EQ(formatNumber(1e300), "1e+300");
  EXPECT_EQ(std::stod(formatNumber(1.0 / 3.0)), 1.0 / 3.0);
  EXPECT_EQ(formatNumber(std::nan("")), "nan");
  EXPECT_EQ(formatNumber(-HUGE_VAL), "-inf");
}

TEST(MetricsReport, AggregateGivesMeanSampleStdMinMax) {
  // GIVEN four runs with d_NB 1, 2, 3, 4 and a metric that is NaN in one run
  std::vector<Summary> runs(4);
  for (int i = 0; i < 4; ++i) {
    runs[static_cast<std::size_t>(i)].mean_neighbor_distance_m = 1.0 + i;
    runs[static_cast<std::size_t>(i)].collisions = static_cast<std::uint64_t>(2 * i);
    runs[static_cast<std::size_t>(i)].anees_position = i == 2 ? std::nan("") : 1.0;
  }
  // WHEN aggregated
  const Aggregate agg = aggregate(runs);
  // THEN mean 2.5, sample std sqrt(5/3), min 1, max 4
  EXPECT_EQ(agg.runs, 4);
  const Statistic* d = agg.find("mean_neighbor_distance_m");
  ASSERT_NE(d, nullptr);
  EXPECT_EQ(d->runs, 4);
  EXPECT_DOUBLE_EQ(d->mean, 2.5);
  EXPECT_NEAR(d->std, std::sqrt(5.0 / 3.0), 1e-12);
  EXPECT_DOUBLE_EQ(d->min, 1.0);
  EXPECT_DOUBLE_EQ(d->max, 4.0);
  // AND counts aggregate like any number: collisions 0, 2, 4, 6
  const Statistic* c = agg.find("collisions");
  ASSERT_NE(c, nullptr);
  EXPECT_DOUBLE_EQ(c->mean, 3.0);
  EXPECT_NEAR(c->std, std::sqrt(20.0 / 3.0), 1e-12);
  // AND a NaN run is left out and counted
  const Statistic* a = agg.find("anees_position");
  ASSERT_NE(a, nullptr);
  EXPECT_EQ(a->runs, 3);
  EXPECT_DOUBLE_EQ(a->mean, 1.0);
  EXPECT_DOUBLE_EQ(a->std, 0.0);
  // AND a key no run has a value for is all NaN; every summary key is present
  const Statistic* w = agg.find("drift_velocity_mps");
  ASSERT_NE(w, nullptr);
  EXPECT_EQ(w->runs, 0);
  EXPECT_TRUE(std::isnan(w->mean));
  EXPECT_EQ(agg.metrics.size(), summaryFields(Summary{}).size());
  EXPECT_EQ(agg.find("no_such_key"), nullptr);
}

TEST(MetricsReport, AggregateOfNamedValuesMatchesKeysByName) {
  // GIVEN runs listing keys in different orders, one run missing a key
  const std::vector<std::vector<NamedValue>> runs{{{"a", 1.0}, {"b", 10.0}}, {{"b", 20.0}, {"a", 3.0}}, {{"a", 5.0}}};
  const Aggregate agg = aggregate(runs);
  // THEN keys keep the order they first appeared in and are matched by name
  ASSERT_EQ(agg.metrics.size(), 2u);
  EXPECT_EQ(agg.metrics[0].key, "a");
  EXPECT_DOUBLE_EQ(agg.metrics[0].mean, 3.0);
  EXPECT_DOUBLE_EQ(agg.metrics[0].std, 2.0);
  EXPECT_EQ(agg.metrics[1].runs, 2);
  EXPECT_DOUBLE_EQ(agg.metrics[1].mean, 15.0);
  // AND a single value has std 0
  const Aggregate one = aggregate(std::vector<std::vector<NamedValue>>{{{"x", 7.0}}});
  EXPECT_DOUBLE_EQ(one.metrics[0].std, 0.0);
  EXPECT_DOUBLE_EQ(one.metrics[0].min, 7.0);
}

}  // namespace
}  // namespace swa::monitor

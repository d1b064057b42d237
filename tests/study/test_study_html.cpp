// study.html (deploy/programs/study/study_html.cpp, study_plots.cpp): a title that says what the study varies,
// categories drawn as categories, drift against N on log-log axes with an N^-1/2 guide, the run report's bands, series
// that stay apart, and the numbers of every grid point. Studies built in memory: no simulation.

#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <string>
#include <vector>

#include "markup_support.h"
#include "study_html.h"
#include "study_plots.h"
#include "study_record.h"
#include "swa/monitor/report_html.h"

namespace swa::study {
namespace {

constexpr std::size_t kUavAxis = 0;
constexpr std::size_t kRuleAxis = 1;

// The value of run (point, seed offset) of every metric the page reads: distinct per grid point and seed, so a
// table or a plot that mixes them up shows.
double dNb(std::size_t point, int seed) { return 10.0 + 0.1 * static_cast<double>(point) + 0.01 * seed; }
double drift(std::size_t point, int seed) { return 0.04 + 0.001 * static_cast<double>(point) + 0.002 * seed; }

// uav_count = 4, 8, 16, 32 × neighbourhood = gabriel, k_nearest, 2 seeds; every run without a collision (equal
// values in both series); each uav_count its own ANEES band, as K = N agents gives.
StudyRecord driftStudy(const std::string& scenario_yaml = "uav_count: 4\n") {
  StudyRecord s;
  s.version = "test";
  s.scenario = "deploy/scenarios/study_drift_vs_n.yaml";
  s.scenario_yaml = scenario_yaml;
  s.first_seed = 1;
  s.plan.axes = {parseSweep("uav_count=4,8,16,32"), parseSweep("agent.formation.neighbourhood=gabriel,k_nearest")};
  s.plan.seeds = 2;
  s.study_id = studyId(s.version, s.scenario_yaml, s.plan, s.first_seed);
  for (const RunRef& r : shardRuns(s.plan, s.shard)) {
    const double n = std::stod(pointValues(s.plan, r.point)[kUavAxis]);
    s.runs.push_back({r.index,
                      r.point,
                      s.first_seed + static_cast<std::uint64_t>(r.seed_offset),
                      {{"mean_neighbor_distance_m", dNb(r.point, r.seed_offset)},
                       {"drift_velocity_mps", drift(r.point, r.seed_offset)},
                       {"collisions", 0.0},
                       {"anees_position", 2.0},
                       {"anees_band_low", 2.0 - 4.0 / std::sqrt(n)},
                       {"anees_band_high", 2.0 + 4.0 / std::sqrt(n)}}});
  }
  return s;
}

const StudyMetric& metric(const std::string& key) {
  for (const StudyMetric& m : studyMetrics()) {
    if (m.key == key) return m;
  }
  throw std::invalid_argument("no metric " + key);
}

// The <figure> of study.html whose plot has this title.
std::string figureTitled(const std::string& html, const std::string& title) {
  const std::size_t at = html.find(">" + title + "</text>");
  if (at == std::string::npos) return "";
  const std::size_t begin = html.rfind("<figure>", at);
  return html.substr(begin, html.find("</figure>", at) - begin);
}

TEST(StudyHtml, TitleSaysWhatIsSweptAndOnWhichScenarioAndKeepsTheIdInTheTable) {
  const StudyRecord s = driftStudy();
  const std::string html = studyHtml(s);
  const std::string title = studyTitle(s);
  EXPECT_NE(title.find("uav_count"), std::string::npos) << title;
  EXPECT_NE(title.find("agent.formation.neighbourhood"), std::string::npos) << title;
  EXPECT_NE(title.find("scenario study_drift_vs_n"), std::string::npos) << title;
  EXPECT_EQ(title.find(s.study_id), std::string::npos) << "the hash names nothing a reader knows";
  EXPECT_NE(html.find("<title>" + title + "</title>"), std::string::npos);
  EXPECT_NE(html.find("<h1>" + title + "</h1>"), std::string::npos);
  EXPECT_NE(html.find("<tr><th>study id</th><td>" + s.study_id + "</td></tr>"), std::string::npos);
  // Variants are named by their names.
  StudyRecord v = s;
  v.plan.axes.pop_back();
  setVariants(v.plan, {parseVariant("gabriel:agent.formation.neighbourhood=gabriel"),
                       parseVariant("k3:agent.formation.neighbourhood=k_nearest,agent.formation.k=3")});
  EXPECT_NE(studyTitle(v).find("against uav_count and variants gabriel and k3"), std::string::npos) << studyTitle(v);
}

TEST(StudyHtml, ACategoricalAxisHasItsNamesAsTicksAndMarkersNotALine) {
  const std::string html = studyHtml(driftStudy());
  const std::string section = html.substr(html.find("<h2>Against agent.formation.neighbourhood</h2>"));
  const std::string d_nb = figureTitled(section, "d_NB (final) against agent.formation.neighbourhood, by uav_count");
  ASSERT_FALSE(d_nb.empty());
  EXPECT_EQ(monitor::testing::texts(d_nb, "tick-x"), (std::vector<std::string>{"gabriel", "k_nearest"}));
  EXPECT_EQ(html.find("0 = gabriel"), std::string::npos) << "no footnote decoding numbers into names";
  EXPECT_EQ(section.find("class=\"series\""), std::string::npos) << "no line joins two categories";
  EXPECT_NE(d_nb.find("class=\"error-bar\""), std::string::npos);
  // Each of the 4 uav_count series has a marker at both categories.
  const StudyPlot plot = studyPlot(StudyView(driftStudy()), kRuleAxis, metric("mean_neighbor_distance_m"));
  ASSERT_EQ(plot.spec.series.size(), 4u);
  for (const monitor::PlotSeries& s : plot.spec.series) {
    EXPECT_NE(s.marker, monitor::MarkerShape::kNone);
    EXPECT_FALSE(s.joined);
    ASSERT_EQ(s.x.size(), 2u);
    EXPECT_NEAR(s.x[0], 0.0, 0.2);
    EXPECT_NEAR(s.x[1], 1.0, 0.2);
  }
}

TEST(StudyHtml, DriftAgainstUavCountIsLogLogWithAnAnchoredInverseSquareRootGuide) {
  const StudyRecord s = driftStudy();
  const StudyPlot plot = studyPlot(StudyView(s), kUavAxis, metric("drift_velocity_mps"));
  EXPECT_TRUE(plot.spec.x_log);
  EXPECT_TRUE(plot.spec.y_log);
  EXPECT_EQ(plot.spec.x_tick_labels, (std::vector<std::string>{"4", "8", "16", "32"}));
  const monitor::PlotSeries* guide = nullptr;
  for (const monitor::PlotSeries& series : plot.spec.series) {
    if (series.label == "∝ N^-1/2") guide = &series;
  }
  ASSERT_NE(guide, nullptr);
  EXPECT_FALSE(guide->dash_pattern.empty()) << "dashed: a guide, not data";
  // Through the mean of every run at N = 4 (grid points 0 and 1, both seeds), falling as N^-1/2 from there.
  const double anchor = (drift(0, 0) + drift(0, 1) + drift(1, 0) + drift(1, 1)) / 4.0;
  ASSERT_EQ(guide->x, (std::vector<double>{4.0, 8.0, 16.0, 32.0}));
  for (std::size_t i = 0; i < guide->x.size(); ++i) {
    EXPECT_NEAR(guide->y[i], anchor * std::sqrt(4.0 / guide->x[i]), 1e-12) << i;
  }
  EXPECT_NE(studyHtml(s).find(">∝ N^-1/2</text>"), std::string::npos) << "in the legend";
  // Against a categorical key the drift stays linear.
  const StudyPlot categorical = studyPlot(StudyView(s), kRuleAxis, metric("drift_velocity_mps"));
  EXPECT_FALSE(categorical.spec.x_log);
  EXPECT_FALSE(categorical.spec.y_log);
}

TEST(StudyHtml, DNbHasTheRunReportsBandRPlusMinusFivePercentOfTheScenario) {
  // GIVEN a scenario whose r is 12 m
  const StudyRecord s = driftStudy("uav_count: 4\nagent:\n  formation:\n    radius_m: 12.0\n");
  const StudyPlot plot = studyPlot(StudyView(s), kUavAxis, metric("mean_neighbor_distance_m"));
  // THEN one band across the plot, 12 m ± 5 %, and r itself as a line
  ASSERT_EQ(plot.spec.bands.size(), 1u);
  EXPECT_DOUBLE_EQ(plot.spec.bands[0].low, 12.0 * 0.95);
  EXPECT_DOUBLE_EQ(plot.spec.bands[0].high, 12.0 * 1.05);
  EXPECT_EQ(plot.spec.bands[0].label, "r ± 5 %");
  EXPECT_TRUE(std::isnan(plot.spec.bands[0].x_low));
  ASSERT_EQ(plot.spec.lines.size(), 1u);
  EXPECT_DOUBLE_EQ(plot.spec.lines[0].value, 12.0);
  // AND a sweep of r gives each value its own band over its share of the axis
  StudyRecord swept = driftStudy();
  swept.plan.axes[kRuleAxis] = parseSweep("agent.formation.radius_m=8,12");
  const StudyPlot per_point = studyPlot(StudyView(swept), kRuleAxis, metric("mean_neighbor_distance_m"));
  ASSERT_EQ(per_point.spec.bands.size(), 2u);
  EXPECT_DOUBLE_EQ(per_point.spec.bands[0].low, 8.0 * 0.95);
  EXPECT_DOUBLE_EQ(per_point.spec.bands[0].x_high, 10.0) << "halfway to the next value";
  EXPECT_DOUBLE_EQ(per_point.spec.bands[1].high, 12.0 * 1.05);
  EXPECT_DOUBLE_EQ(per_point.spec.bands[1].x_low, 10.0);
  EXPECT_TRUE(per_point.spec.lines.empty()) << "no one r to draw";
  // AND the page draws the band
  const std::string figure =
      figureTitled(studyHtml(s), "d_NB (final) against uav_count, by agent.formation.neighbourhood");
  EXPECT_NE(figure.find("class=\"band\""), std::string::npos);
  EXPECT_NE(figure.find(">r ± 5 %</text>"), std::string::npos);
}

TEST(StudyHtml, AneesHasEachRunsChiSquareBandAtItsValue) {
  const StudyPlot plot = studyPlot(StudyView(driftStudy()), kUavAxis, metric("anees_position"));
  ASSERT_EQ(plot.spec.bands.size(), 4u) << "K = N differs between the sizes: a band per size";
  EXPECT_DOUBLE_EQ(plot.spec.bands[0].low, 2.0 - 4.0 / 2.0);
  EXPECT_DOUBLE_EQ(plot.spec.bands[3].high, 2.0 + 4.0 / std::sqrt(32.0));
  EXPECT_TRUE(std::isnan(plot.spec.bands[0].x_low)) << "the first reaches the plot's edge";
  EXPECT_DOUBLE_EQ(plot.spec.bands[1].x_low, 6.0);
  EXPECT_DOUBLE_EQ(plot.spec.bands[1].x_high, 12.0);
  ASSERT_EQ(plot.spec.lines.size(), 1u);
  EXPECT_DOUBLE_EQ(plot.spec.lines[0].value, 2.0);
  // Against the rule the band changes with the series (uav_count): each marker has its own band behind it.
  const StudyPlot by_rule = studyPlot(StudyView(driftStudy()), kRuleAxis, metric("anees_position"));
  ASSERT_EQ(by_rule.spec.bands.size(), 8u);
  for (const monitor::PlotBand& band : by_rule.spec.bands) {
    std::size_t behind = 0;
    for (const monitor::PlotSeries& s : by_rule.spec.series) {
      for (const double x : s.x) behind += x > band.x_low && x < band.x_high ? 1 : 0;
    }
    EXPECT_EQ(behind, 1u) << "a band behind exactly one marker, [" << band.x_low << ", " << band.x_high << "]";
  }
}

TEST(StudyHtml, SeriesDifferInColourShapeAndDashAndEqualValuesStayApart) {
  const StudyPlot plot = studyPlot(StudyView(driftStudy()), kUavAxis, metric("collisions"));
  ASSERT_EQ(plot.spec.series.size(), 2u);
  const monitor::PlotSeries& a = plot.spec.series[0];
  const monitor::PlotSeries& b = plot.spec.series[1];
  EXPECT_NE(a.colour, b.colour);
  EXPECT_NE(a.marker, b.marker);
  EXPECT_NE(a.dash_pattern, b.dash_pattern);
  ASSERT_EQ(a.y, b.y) << "every run without a collision";
  const std::vector<double> values{4.0, 8.0, 16.0, 32.0};
  ASSERT_EQ(a.x.size(), values.size());
  for (std::size_t i = 0; i < a.x.size(); ++i) {
    EXPECT_LT(a.x[i], b.x[i]) << "side by side at value " << i;
    EXPECT_NEAR(0.5 * (a.x[i] + b.x[i]), values[i], 1e-9) << "centred on the value";
  }
  ASSERT_EQ(plot.spec.lines.size(), 1u);
  EXPECT_EQ(plot.spec.lines[0].value, 0.0);
}

TEST(StudyHtml, TheNumbersHaveEveryGridPointsMeanSdAndN) {
  const StudyRecord s = driftStudy();
  const std::string html = studyHtml(s);
  const std::size_t table = html.find("<table class=\"numbers\" data-metric=\"mean_neighbor_distance_m\">");
  ASSERT_NE(table, std::string::npos);
  const std::string d_nb = html.substr(table, html.find("</table>", table) - table);
  for (std::size_t point = 0; point < pointCount(s.plan); ++point) {
    const std::vector<std::string> v = pointValues(s.plan, point);
    const double mean = 0.5 * (dNb(point, 0) + dNb(point, 1));
    const double sd = std::fabs(dNb(point, 1) - dNb(point, 0)) / std::sqrt(2.0);
    const std::string row = "<tr><td>" + v[0] + "</td><td>" + v[1] + "</td><td class=\"num\">" +
                            monitor::formatReportValue(mean) + "</td><td class=\"num\">" +
                            monitor::formatReportValue(sd) + "</td><td class=\"num\">2</td></tr>";
    EXPECT_NE(d_nb.find(row), std::string::npos) << row << "\n" << d_nb;
  }
  // After every plot.
  EXPECT_GT(table, html.rfind("</figure>"));
}

TEST(StudyHtml, IsDeterministicSelfContainedAndEscaped) {
  StudyRecord s = driftStudy();
  s.scenario = "a<b>&.yaml";
  const std::string html = studyHtml(s);
  EXPECT_EQ(html, studyHtml(s));
  EXPECT_NE(html.find("scenario a&lt;b&gt;&amp;</title>"), std::string::npos);
  EXPECT_EQ(html.find("a<b>"), std::string::npos);
  for (const char* external : {"<script", "<link", "<img", "src=", "href=", "url("}) {
    EXPECT_EQ(html.find(external), std::string::npos) << external;
  }
}

}  // namespace
}  // namespace swa::study

// Report additions used by swa_monitor: free tables after the summary (events, agent restarts), and reading a
// Summary back from its flat key/value view (summaryFromFields, the inverse of summaryFields).

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "swa/monitor/report_html.h"
#include "swa/monitor/summary_format.h"

namespace swa::monitor {
namespace {

std::string sectionOf(const std::string& html, const std::string& id) {
  const std::size_t begin = html.find("<section id=\"" + id + "\">");
  if (begin == std::string::npos) return "";
  return html.substr(begin, html.find("</section>", begin) - begin);
}

TEST(ReportTables, RenderedAfterTheSummaryEscapedAndPadded) {
  ReportNotes notes;
  ReportTable t;
  t.id = "events";
  t.title = "Scenario events";
  t.note = "times in <s>";
  t.columns = {"time", "event", "detail"};
  t.rows = {{"1.5", "collision", "a & b"}, {"2"}};
  notes.tables.push_back(t);
  ReportTable empty;
  empty.id = "restarts";
  empty.title = "Agent restarts";
  empty.columns = {"x"};
  empty.empty_text = "No agent restart.";
  notes.tables.push_back(empty);
  RunReport run;
  run.label = "swa";
  const std::string html = renderReportHtml({run}, notes);

  const std::string events = sectionOf(html, "table-events");
  ASSERT_FALSE(events.empty());
  EXPECT_NE(events.find("<h2>Scenario events</h2>"), std::string::npos);
  EXPECT_NE(events.find("<p>times in &lt;s&gt;</p>"), std::string::npos);
  EXPECT_NE(events.find("<td>a &amp; b</td>"), std::string::npos);
  EXPECT_NE(events.find("<tr><td>2</td><td></td><td></td></tr>"), std::string::npos);  // short row padded
  const std::string restarts = sectionOf(html, "table-restarts");
  EXPECT_NE(restarts.find("<p>No agent restart.</p>"), std::string::npos);
  EXPECT_EQ(restarts.find("<table"), std::string::npos);
  // After the summary, and after the plots: the verdict and the pictures come first (issue #30).
  EXPECT_LT(html.find("id=\"summary\""), html.find("id=\"table-events\""));
  EXPECT_LT(html.find("id=\"plots\""), html.find("id=\"table-events\""));
  EXPECT_LT(html.find("id=\"trajectories\""), html.find("id=\"table-restarts\""));
}

TEST(ReportTables, UnsafeIdIsReduced) {
  ReportNotes notes;
  ReportTable t;
  t.id = "a b\"<c>";
  t.title = "T";
  notes.tables.push_back(t);
  const std::string html = renderReportHtml({}, notes);
  EXPECT_NE(html.find("<section id=\"table-a_b__c_\">"), std::string::npos);
}

TEST(SummaryFields, ReadBackIsTheInverse) {
  Summary s;
  s.steps = 301;
  s.duration_s = 30.0;
  s.mean_neighbor_distance_m = 9.87;
  s.collisions = 4;
  s.groups = 2;
  s.anees_position = kNaN;
  s.nees_samples = 1ull << 40;
  s.anees_agents = 4;
  const Summary back = summaryFromFields(summaryFields(s));
  const auto a = summaryFields(s);
  const auto b = summaryFields(back);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k) {
    EXPECT_EQ(a[k].key, b[k].key);
    EXPECT_TRUE((std::isnan(a[k].value) && std::isnan(b[k].value)) || a[k].value == b[k].value) << a[k].key;
  }
}

TEST(SummaryFields, MissingNaNAndOddCountsKeepDefaults) {
  const Summary s = summaryFromFields({{"steps", kNaN},
                                       {"collisions", -3.0},
                                       {"groups", 2.6},
                                       {"unknown", 1.0},
                                       {"min_separation_m", 7.5},
                                       {"nees_samples", 1e30},
                                       {"anees_agents", -1e30}});
  EXPECT_EQ(s.steps, 0);        // NaN count: default
  EXPECT_EQ(s.collisions, 0u);  // negative unsigned count: clamped
  EXPECT_EQ(s.groups, 3);       // rounded
  EXPECT_EQ(s.min_separation_m, 7.5);
  EXPECT_GT(s.nees_samples, 1ull << 63);  // clamped below 2^64, no overflow
  EXPECT_EQ(s.anees_agents, std::numeric_limits<int>::lowest());
  EXPECT_TRUE(std::isnan(s.duration_s));  // missing: Summary{}'s default
}

}  // namespace
}  // namespace swa::monitor

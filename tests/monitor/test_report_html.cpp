// The monitor's report.html: summary table, plots, notes, escaping, self-containment, determinism, the side-by-side
// comparison of runs, and the trajectory decimation that feeds it.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "markup_support.h"
#include "swa/monitor/report_html.h"

namespace swa::monitor {
namespace {

using testing::elements;
using testing::num;
using testing::occurrences;

// The <figure id="plot-<name>"> ... </figure> block of the report.
std::string figure(const std::string& html, const std::string& name) {
  const std::size_t begin = html.find("<figure id=\"plot-" + name + "\">");
  if (begin == std::string::npos) return "";
  return html.substr(begin, html.find("</figure>", begin) - begin);
}

const ReportPlot* plotNamed(const std::vector<ReportPlot>& plots, const std::string& name) {
  for (const ReportPlot& p : plots) {
    if (p.name == name) return &p;
  }
  return nullptr;
}

// A 20 s run at 2 Hz: d_NB settling at `d_nb_end`, a NEES that is NaN before t = 5 s, three UAVs moving east.
RunReport makeRun(const std::string& label, double d_nb_end, bool with_nees) {
  RunReport run;
  run.label = label;
  run.verdict = "PASS";
  for (int k = 0; k <= 40; ++k) {
    TimeSeriesRow row;
    row.t_s = 0.5 * k;
    row.d_nb_m = d_nb_end + 0.5 * std::exp(-0.2 * row.t_s);
    row.drift_mps = 0.05;
    row.min_sep_m = 8.0 - 0.1 * row.t_s;
    row.nees_pos = (with_nees && row.t_s >= 5.0) ? 1.5 + 0.5 * (k % 3) : kNaN;
    run.series.push_back(row);
  }
  for (int id = 0; id < 3; ++id) {
    UavTrajectory t;
    t.id = id;
    for (int k = 0; k <= 20; ++k) {
      t.points.push_back({1.0 * k, 2.0 * k + 10.0 * id, 5.0 * id});
    }
    run.trajectories.push_back(t);
  }
  run.summary.steps = 41;
  run.summary.duration_s = 20.0;
  run.summary.window_start_s = 5.0;
  run.summary.uav_count = 3;
  run.summary.mean_neighbor_distance_m = d_nb_end;
  run.summary.collisions = 0;
  if (with_nees) {
    run.summary.anees_position = 2.0;
    run.summary.anees_agents = 3;
    run.summary.anees_band_low = 0.5;
    run.summary.anees_band_high = 3.5;
  }
  return run;
}

ReportNotes makeNotes() {
  ReportNotes notes;
  notes.scenario = "dropout_8";
  notes.seeds = {1, 2, 3};
  notes.version = "0.1.0";
  notes.gnss_loss_s = 5.0;
  return notes;
}

TEST(ReportHtml, EverySummaryKeyHasARowWithOneCellPerRun) {
  // GIVEN two runs side by side, one with NEES and one without
  const std::vector<RunReport> runs{makeRun("swa", 9.75, true), makeRun("standalone", 21.5, false)};
  // WHEN the report is rendered
  const std::string html = renderReportHtml(runs, makeNotes());
  // THEN every summaryFields key is a row header exactly once, and the table has one column per run
  for (const NamedValue& f : summaryFields(Summary{})) {
    EXPECT_EQ(occurrences(html, "<th scope=\"row\">" + f.key + "</th>"), 1) << f.key;
  }
  EXPECT_NE(html.find("<th scope=\"col\">metric</th><th scope=\"col\">swa</th><th scope=\"col\">standalone</th>"),
            std::string::npos);
  // AND values are formatted per run, a missing one as a dash, counts as integers
  EXPECT_NE(html.find("<tr><th scope=\"row\">mean_neighbor_distance_m</th><td>9.75</td><td>21.5</td></tr>"),
            std::string::npos);
  EXPECT_NE(html.find("<tr><th scope=\"row\">anees_position</th><td>2</td><td>—</td></tr>"), std::string::npos);
  EXPECT_NE(html.find("<tr><th scope=\"row\">steps</th><td>41</td><td>41</td></tr>"), std::string::npos);
}

TEST(ReportHtml, AllTextIsEscaped) {
  // GIVEN markup characters in every caller-supplied text
  RunReport run = makeRun("a<b>&\"c\"", 10.0, true);
  run.verdict = "FAIL <d_NB> & \"drift\"";
  ReportNotes notes = makeNotes();
  notes.title = "<title>&";
  notes.scenario = "<script>alert(1)</script>";
  notes.version = "1.0 \"<beta>\"";
  notes.extra = {{"<key>", "a & b"}};
  // WHEN rendered
  const std::string html = renderReportHtml({run}, notes);
  // THEN each appears only escaped, and nothing injected survives as markup
  EXPECT_NE(html.find("<th scope=\"col\">a&lt;b&gt;&amp;&quot;c&quot;</th>"), std::string::npos);
  EXPECT_NE(html.find("FAIL &lt;d_NB&gt; &amp; &quot;drift&quot;"), std::string::npos);
  EXPECT_NE(html.find("<title>&lt;title&gt;&amp;</title>"), std::string::npos);
  EXPECT_NE(html.find("&lt;script&gt;alert(1)&lt;/script&gt;"), std::string::npos);
  EXPECT_NE(html.find("1.0 &quot;&lt;beta&gt;&quot;"), std::string::npos);
  EXPECT_NE(html.find("<dt>&lt;key&gt;</dt><dd>a &amp; b</dd>"), std::string::npos);
  EXPECT_EQ(html.find("<script"), std::string::npos);
  EXPECT_EQ(html.find("a<b>"), std::string::npos);
  EXPECT_EQ(html.find("<beta>"), std::string::npos);
  EXPECT_EQ(html.find("<d_NB>"), std::string::npos);
  // AND the legends inside the inline SVGs are escaped too
  EXPECT_NE(figure(html, "d_nb").find(">a&lt;b&gt;&amp;&quot;c&quot;</text>"), std::string::npos);
}

TEST(ReportHtml, IsSelfContained) {
  const std::string html = renderReportHtml({makeRun("swa", 10.0, true)}, makeNotes());
  EXPECT_EQ(html.rfind("<!DOCTYPE html>\n<html lang=\"en\">", 0), 0U);
  EXPECT_NE(html.find("<meta charset=\"utf-8\">"), std::string::npos);
  EXPECT_EQ(html.substr(html.size() - 8), "</html>\n");
  for (const char* external : {"<script", "<link", "<img", "<iframe", "src=", "href=", "url(", "@import"}) {
    EXPECT_EQ(html.find(external), std::string::npos) << external;
  }
  EXPECT_EQ(occurrences(html, "<style>"), 1);
}

TEST(ReportHtml, NotesNameScenarioSeedsAndVersion) {
  const std::string html = renderReportHtml({makeRun("swa", 10.0, true)}, makeNotes());
  EXPECT_NE(html.find("<dt>Scenario</dt><dd>dropout_8</dd>"), std::string::npos);
  EXPECT_NE(html.find("<dt>Seeds</dt><dd>1, 2, 3</dd>"), std::string::npos);
  EXPECT_NE(html.find("<dt>Version</dt><dd>0.1.0</dd>"), std::string::npos);
  EXPECT_NE(html.find("<dt>GNSS lost at</dt><dd>5 s</dd>"), std::string::npos);
  // AND missing notes are a dash, not an empty cell
  ReportNotes bare;
  const std::string plain = renderReportHtml({makeRun("swa", 10.0, true)}, bare);
  EXPECT_NE(plain.find("<dt>Seeds</dt><dd>—</dd>"), std::string::npos);
}

TEST(ReportHtml, ComparisonPlotsHoldEveryRunAndTheirReferences) {
  // GIVEN swa and standalone
  const std::vector<RunReport> runs{makeRun("swa", 9.75, true), makeRun("standalone", 21.5, false)};
  const ReportNotes notes = makeNotes();
  // WHEN the plots are built
  const std::vector<ReportPlot> plots = reportPlots(runs, notes);
  // THEN there are the four time plots and one trajectory plot per run, in order
  ASSERT_EQ(plots.size(), 6U);
  EXPECT_EQ(plots[0].name, "d_nb");
  EXPECT_EQ(plots[1].name, "drift");
  EXPECT_EQ(plots[2].name, "min_separation");
  EXPECT_EQ(plots[3].name, "nees_position");
  EXPECT_EQ(plots[4].name, "trajectories_swa");
  EXPECT_EQ(plots[5].name, "trajectories_standalone");
  // AND d_NB shows both runs on one plot, in their palette colours, with the band r ± 5 % (the default PASS band)
  // and the GNSS loss line
  const PlotSpec& d_nb = plots[0].spec;
  ASSERT_EQ(d_nb.series.size(), 2U);
  EXPECT_EQ(d_nb.series[0].label, "swa");
  EXPECT_EQ(d_nb.series[1].label, "standalone");
  EXPECT_EQ(d_nb.series[0].colour, paletteColour(0));
  EXPECT_EQ(d_nb.series[1].colour, paletteColour(1));
  ASSERT_EQ(d_nb.bands.size(), 1U);
  EXPECT_DOUBLE_EQ(d_nb.bands[0].low, 9.5);
  EXPECT_DOUBLE_EQ(d_nb.bands[0].high, 10.5);
  bool loss_line = false;
  for (const PlotLine& l : d_nb.lines) loss_line |= l.orientation == LineOrientation::kVertical && l.value == 5.0;
  EXPECT_TRUE(loss_line);
  // AND the minimum separation plot has the 1.5 m collision line
  bool collision_line = false;
  for (const PlotLine& l : plots[2].spec.lines) {
    collision_line |= l.orientation == LineOrientation::kHorizontal && l.value == 1.5;
  }
  EXPECT_TRUE(collision_line);
  // AND the stacked time plots line up (same plot area)
  const PlotLayout first = layoutPlot(plots[0].spec);
  for (std::size_t i = 1; i < 4; ++i) {
    EXPECT_EQ(layoutPlot(plots[i].spec).right_px, first.right_px) << plots[i].name;
  }
}

TEST(ReportHtml, DnbBandIsDrawnWhereTheAxisPutsIt) {
  // GIVEN one run and r = 10 m
  const std::vector<RunReport> runs{makeRun("swa", 9.75, true)};
  const ReportNotes notes = makeNotes();
  const std::string html = renderReportHtml(runs, notes);
  const PlotLayout l = layoutPlot(reportPlots(runs, notes)[0].spec);
  // WHEN the d_NB figure is inspected THEN its band rect runs from y(10.5 m) to y(9.5 m)
  const std::vector<std::string> bands = elements(figure(html, "d_nb"), "rect", "band");
  ASSERT_EQ(bands.size(), 1U);
  EXPECT_NEAR(num(bands[0], "y"), l.yToPx(10.5), 0.01);
  EXPECT_NEAR(num(bands[0], "height"), l.yToPx(9.5) - l.yToPx(10.5), 0.01);
  // AND the min separation figure draws its collision line at y(1.5 m)
  const PlotLayout ls = layoutPlot(reportPlots(runs, notes)[2].spec);
  bool found = false;
  for (const std::string& line : elements(figure(html, "min_separation"), "line", "ref-line")) {
    found |= std::fabs(num(line, "y1") - ls.yToPx(1.5)) < 0.01 && std::fabs(num(line, "y2") - ls.yToPx(1.5)) < 0.01;
  }
  EXPECT_TRUE(found);
}

TEST(ReportHtml, NeesPlotHasTheChiSquareBandAndTheRunningAnees) {
  // GIVEN a run with NEES and its summary band [0.5, 3.5], and a run without NEES
  const std::vector<RunReport> runs{makeRun("swa", 10.0, true), makeRun("standalone", 20.0, false)};
  const std::vector<ReportPlot> plots = reportPlots(runs, makeNotes());
  const PlotSpec& nees = plots[3].spec;
  // THEN the band is the summary's, drawn once
  ASSERT_EQ(nees.bands.size(), 1U);
  EXPECT_EQ(nees.bands[0].low, 0.5);
  EXPECT_EQ(nees.bands[0].high, 3.5);
  EXPECT_NE(nees.bands[0].label.find("K = 3"), std::string::npos);
  // AND the run without NEES says so in the legend; the other gets a running ANEES series
  EXPECT_EQ(nees.series[1].label, "standalone (no data)");
  ASSERT_EQ(nees.series.size(), 3U);
  EXPECT_EQ(nees.series[2].label, "swa ANEES");
  // AND the running ANEES ends at the mean of the per-step values in the window (t >= 5 s)
  double sum = 0.0;
  int n = 0;
  for (const TimeSeriesRow& row : runs[0].series) {
    if (row.t_s >= 5.0 && std::isfinite(row.nees_pos)) {
      sum += row.nees_pos;
      ++n;
    }
  }
  EXPECT_NEAR(nees.series[2].y.back(), sum / n, 1e-12);
  EXPECT_TRUE(std::isnan(nees.series[2].y.front()));
  // AND the y axis starts at 0 and shows the whole band
  const PlotLayout l = layoutPlot(nees);
  EXPECT_EQ(l.y.lo, 0.0);
  EXPECT_GE(l.y.hi, 3.5);
}

TEST(ReportHtml, DifferentBandsAreDrawnPerRun) {
  RunReport a = makeRun("k3", 10.0, true);
  RunReport b = makeRun("k8", 10.0, true);
  b.summary.anees_agents = 8;
  b.summary.anees_band_low = 1.2;
  b.summary.anees_band_high = 2.9;
  const PlotSpec nees = reportPlots({a, b}, makeNotes())[3].spec;
  ASSERT_EQ(nees.bands.size(), 2U);
  EXPECT_NE(nees.bands[0].label.find("(k3)"), std::string::npos);
  EXPECT_NE(nees.bands[1].label.find("(k8)"), std::string::npos);
  EXPECT_EQ(nees.bands[1].low, 1.2);
}

TEST(ReportHtml, TrajectoryPlotsHaveEqualScaleAndAMarkerPairPerUav) {
  // GIVEN two runs of three UAVs each
  const std::vector<RunReport> runs{makeRun("swa", 10.0, true), makeRun("standalone", 20.0, false)};
  const std::string html = renderReportHtml(runs, makeNotes());
  const std::vector<ReportPlot> plots = reportPlots(runs, makeNotes());
  for (const char* name : {"trajectories_swa", "trajectories_standalone"}) {
    const ReportPlot* p = plotNamed(plots, name);
    ASSERT_NE(p, nullptr) << name;
    // THEN the plot is equal-aspect: a metre is as long in x as in y
    EXPECT_TRUE(p->spec.equal_aspect);
    const PlotLayout l = layoutPlot(p->spec);
    EXPECT_NEAR(l.xScale(), l.yScale(), 1e-9 * l.xScale()) << name;
    // AND each UAV has one start and one end marker in the report
    const std::string fig = figure(html, name);
    EXPECT_EQ(elements(fig, "circle", "start-marker").size(), 3U) << name;
    EXPECT_EQ(elements(fig, "rect", "end-marker").size(), 3U) << name;
    EXPECT_NE(fig.find(">UAV 2</text>"), std::string::npos) << name;
  }
  // AND the trajectories sit in their own section after the time plots
  EXPECT_LT(html.find("id=\"plot-nees_position\""), html.find("<section id=\"trajectories\">"));
  EXPECT_LT(html.find("<section id=\"trajectories\">"), html.find("id=\"plot-trajectories_swa\""));
}

TEST(ReportHtml, TheVerdictAndThePicturesComeBeforeTheLongTables) {
  // GIVEN a passing and a failing run, and a table of events
  RunReport pass = makeRun("swa", 10.0, true);
  pass.verdict = "PASS: d_NB within 3 % of r";
  RunReport fail = makeRun("standalone", 20.0, false);
  fail.verdict = "FAIL: d_NB 20 m, outside r ± 5 %";
  ReportNotes notes = makeNotes();
  ReportTable events;
  events.id = "events";
  events.title = "Scenario events";
  events.columns = {"time", "event"};
  events.rows = {{"1", "gnss_lost"}};
  notes.tables.push_back(events);
  const std::string html = renderReportHtml({pass, fail}, notes);
  // THEN right under the title each run's verdict with its reasons
  const std::size_t verdict = html.find("<section id=\"verdict\">");
  ASSERT_NE(verdict, std::string::npos);
  EXPECT_EQ(html.find("<section"), verdict) << "the first section";
  EXPECT_NE(html.find("<dt>swa</dt><dd class=\"verdict\">PASS: d_NB within 3 % of r</dd>", verdict), std::string::npos);
  EXPECT_NE(html.find("<dt>standalone</dt><dd class=\"verdict\">FAIL: d_NB 20 m, outside r ± 5 %</dd>", verdict),
            std::string::npos);
  // AND then the plots, and only after them the notes, the summary table and the caller's tables
  const std::size_t plots = html.find("<section id=\"plots\">");
  const std::size_t trajectories = html.find("<section id=\"trajectories\">");
  EXPECT_LT(verdict, plots);
  EXPECT_LT(plots, trajectories);
  for (const char* later : {"<section id=\"notes\">", "<section id=\"summary\">", "<section id=\"table-events\">"}) {
    ASSERT_NE(html.find(later), std::string::npos) << later;
    EXPECT_LT(trajectories, html.find(later)) << later;
  }
}

TEST(ReportHtml, ALargeSwarmsTracksAreLabelledAtTheirEndsInsteadOfALegendTallerThanThePlot) {
  // GIVEN a run of 100 UAVs on a 10 x 10 lattice, and one of 16
  RunReport big = makeRun("swa", 10.0, true);
  big.trajectories.clear();
  for (int id = 0; id < 100; ++id) {
    UavTrajectory t;
    t.id = id;
    for (int k = 0; k <= 4; ++k) t.points.push_back({1.0 * k, 10.0 * (id % 10) + 0.1 * k, 10.0 * (id / 10)});
    big.trajectories.push_back(t);
  }
  RunReport sixteen = big;
  sixteen.label = "sixteen";
  sixteen.trajectories.resize(16);
  const std::vector<ReportPlot> plots = reportPlots({big, sixteen}, makeNotes());
  const ReportPlot* p = plotNamed(plots, "trajectories_swa");
  ASSERT_NE(p, nullptr);
  // THEN the 100-UAV plot keeps its size (no legend row per UAV) and its tracks have no legend entry
  const PlotLayout l = layoutPlot(p->spec);
  EXPECT_DOUBLE_EQ(l.height_px, static_cast<double>(p->spec.height_px));
  EXPECT_TRUE(
      std::all_of(p->spec.series.begin(), p->spec.series.end(), [](const PlotSeries& s) { return s.label.empty(); }));
  // AND each track's end carries its UAV's id, at that end
  const PlotSeries& ends = p->spec.series.back();
  ASSERT_EQ(ends.point_labels.size(), 100U);
  EXPECT_EQ(ends.marker, MarkerShape::kDot);
  EXPECT_EQ(ends.point_labels[37], "37");
  EXPECT_DOUBLE_EQ(ends.x[37], 70.4);
  EXPECT_DOUBLE_EQ(ends.y[37], 30.0);
  EXPECT_NE(p->caption.find("labelled with the UAV's id"), std::string::npos);
  // AND 16 UAVs, the largest shipped swarm, still get their legend
  const ReportPlot* q = plotNamed(plots, "trajectories_sixteen");
  ASSERT_NE(q, nullptr);
  EXPECT_EQ(q->spec.series.size(), 16U);
  EXPECT_EQ(q->spec.series[15].label, "UAV 15");
}

TEST(ReportHtml, PlotNamesAreFileSafeAndUnique) {
  const std::vector<ReportPlot> plots = reportPlots(
      {makeRun("swa k=3/x", 10.0, true), makeRun("swa k=3/x", 10.0, true), makeRun("", 10.0, true)}, makeNotes());
  ASSERT_EQ(plots.size(), 7U);
  EXPECT_EQ(plots[4].name, "trajectories_swa_k_3_x");
  EXPECT_EQ(plots[5].name, "trajectories_swa_k_3_x_2");
  EXPECT_EQ(plots[6].name, "trajectories_run3");
}

TEST(ReportHtml, OutputIsDeterministic) {
  const std::vector<RunReport> runs{makeRun("swa", 9.75, true), makeRun("standalone", 21.5, false)};
  EXPECT_EQ(renderReportHtml(runs, makeNotes()), renderReportHtml(runs, makeNotes()));
}

TEST(ReportHtml, NoRunsStillGivesADocument) {
  const std::string html = renderReportHtml({}, makeNotes());
  EXPECT_NE(html.find("<p>No runs.</p>"), std::string::npos);
  EXPECT_EQ(html.substr(html.size() - 8), "</html>\n");
  EXPECT_EQ(occurrences(html, "<figure "), 4);
}

TEST(ReportValue, Formatting) {
  EXPECT_EQ(formatReportValue(kNaN), "—");
  EXPECT_EQ(formatReportValue(8.0), "8");
  EXPECT_EQ(formatReportValue(-3.0), "-3");
  EXPECT_EQ(formatReportValue(9.167589), "9.1676");
  EXPECT_EQ(formatReportValue(0.0676461), "0.067646");
  EXPECT_EQ(formatReportValue(1.5e-7), "1.5e-07");
}

TEST(WriteReport, WritesTheHtmlAndOneSvgPerPlot) {
  // GIVEN a fresh directory below the test's temp dir
  const std::filesystem::path dir = std::filesystem::path(::testing::TempDir()) / "swa_report_test" / "nested";
  std::filesystem::remove_all(dir.parent_path());
  const std::vector<RunReport> runs{makeRun("swa", 9.75, true), makeRun("standalone", 21.5, false)};
  // WHEN the report is written
  const std::vector<std::string> written = writeReport(dir.string(), runs, makeNotes());
  // THEN report.html comes first and is the rendered document, followed by the six plots as SVG files
  ASSERT_EQ(written.size(), 7U);
  EXPECT_EQ(written[0], (dir / "report.html").string());
  const auto read = [](const std::string& path) {
    std::ifstream file(path, std::ios::binary);
    std::ostringstream text;
    text << file.rdbuf();
    return text.str();
  };
  EXPECT_EQ(read(written[0]), renderReportHtml(runs, makeNotes()));
  EXPECT_EQ(written[1], (dir / "d_nb.svg").string());
  for (std::size_t i = 1; i < written.size(); ++i) {
    const std::string svg = read(written[i]);
    EXPECT_EQ(svg.rfind("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg xmlns=", 0), 0U) << written[i];
  }
  std::filesystem::remove_all(dir.parent_path());
}

TEST(WriteReport, UnwritableDirectoryThrows) {
  // GIVEN a path below a regular file
  const std::filesystem::path file = std::filesystem::path(::testing::TempDir()) / "swa_report_not_a_dir";
  std::ofstream(file) << "x";
  EXPECT_THROW(writeReport((file / "sub").string(), {}, makeNotes()), std::runtime_error);
  std::filesystem::remove(file);
}

UavTruth uav(int id, double x, double y, bool alive = true) {
  UavTruth u;
  u.id = id;
  u.position_m = agent::Vec2(x, y);
  u.alive = alive;
  return u;
}

TEST(TrajectoryRecorder, DecimatesToThePeriodAndKeepsTheLastPosition) {
  // GIVEN a recorder at 0.5 s fed at 10 Hz for 1.25 s
  TrajectoryRecorder recorder(0.5);
  for (int k = 0; k <= 12; ++k) {
    const double t = 0.1 * k;
    recorder.add(t, {uav(1, t, 0.0), uav(0, 0.0, t)});
  }
  // WHEN the trajectories are taken
  const std::vector<UavTrajectory> tracks = recorder.trajectories();
  // THEN they are ordered by id, with points at 0, 0.5, 1.0 and the final 1.2 s position
  ASSERT_EQ(tracks.size(), 2U);
  EXPECT_EQ(tracks[0].id, 0);
  EXPECT_EQ(tracks[1].id, 1);
  ASSERT_EQ(tracks[1].points.size(), 4U);
  EXPECT_NEAR(tracks[1].points[1].t_s, 0.5, 1e-12);
  EXPECT_NEAR(tracks[1].points[2].x_m, 1.0, 1e-12);
  EXPECT_NEAR(tracks[1].points[3].t_s, 1.2, 1e-12);
  EXPECT_NEAR(tracks[1].points[3].x_m, 1.2, 1e-12);
  EXPECT_NEAR(tracks[0].points[3].y_m, 1.2, 1e-12);
}

TEST(TrajectoryRecorder, AnAbsentUavBreaksItsLine) {
  // GIVEN UAV 1 present until 0.3 s, absent (dead) at 0.5 s, back at 1.0 s; recording every 0.5 s
  TrajectoryRecorder recorder(0.5);
  for (int k = 0; k <= 10; ++k) {
    const double t = 0.1 * k;
    const bool alive = k <= 3 || k >= 10;
    recorder.add(t, {uav(0, 0.0, 0.0), uav(1, 10.0 + t, 0.0, alive)});
  }
  const std::vector<UavTrajectory> tracks = recorder.trajectories();
  ASSERT_EQ(tracks.size(), 2U);
  // THEN its track is: t = 0, its last seen position at 0.3 s, a gap at 0.5 s, then t = 1.0
  const std::vector<TrajectoryPoint>& p = tracks[1].points;
  ASSERT_EQ(p.size(), 4U);
  EXPECT_NEAR(p[1].t_s, 0.3, 1e-12);
  EXPECT_NEAR(p[1].x_m, 10.3, 1e-12);
  EXPECT_TRUE(std::isnan(p[2].x_m));
  EXPECT_NEAR(p[3].x_m, 11.0, 1e-12);
  // AND in the report the line is split into two pieces, with one start and one end marker
  RunReport run;
  run.label = "gap";
  run.trajectories = tracks;
  const std::string svg = renderSvg(reportPlots({run}, ReportNotes{})[4].spec);
  int pieces_of_uav1 = 0;
  for (const std::string& line : elements(svg, "polyline", "series")) {
    pieces_of_uav1 += line.find("data-series=\"1\"") != std::string::npos ? 1 : 0;
  }
  for (const std::string& dot : elements(svg, "circle", "point")) {
    pieces_of_uav1 += dot.find("data-series=\"1\"") != std::string::npos ? 1 : 0;
  }
  EXPECT_EQ(pieces_of_uav1, 2);
  EXPECT_EQ(elements(svg, "circle", "start-marker").size(), 2U);
}

TEST(TrajectoryRecorder, RejectsABadPeriod) {
  EXPECT_THROW(TrajectoryRecorder(-1.0), std::invalid_argument);
  EXPECT_THROW(TrajectoryRecorder(std::nan("")), std::invalid_argument);
}

}  // namespace
}  // namespace swa::monitor

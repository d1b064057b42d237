// The live page's pictures: the swarm from above and the metric plots, drawn by the report's engine (svg_plot.h) in
// the monitor, so the page shows the report's palette, ticks and bands.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "live_pictures.h"
#include "swa/monitor/svg_plot.h"

namespace swa::live {
namespace {

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();

// Every opening tag <name ... class="cls" ...>.
std::vector<std::string> tags(const std::string& svg, const std::string& name, const std::string& cls) {
  std::vector<std::string> out;
  for (std::size_t pos = svg.find("<" + name + " "); pos != std::string::npos;
       pos = svg.find("<" + name + " ", pos + 1)) {
    const std::string tag = svg.substr(pos, svg.find('>', pos) - pos);
    if (tag.find("class=\"" + cls + "\"") != std::string::npos) out.push_back(tag);
  }
  return out;
}

std::string attribute(const std::string& tag, const std::string& name) {
  const std::size_t begin = tag.find(" " + name + "=\"") + name.size() + 3;
  return tag.substr(begin, tag.find('"', begin) - begin);
}

SwarmScene scene(std::vector<std::pair<double, double>> positions) {
  SwarmScene s;
  for (std::size_t i = 0; i < positions.size(); ++i) {
    s.uavs.push_back({static_cast<int>(i), positions[i].first, positions[i].second, 0.0, 0.0, true});
  }
  return s;
}

TEST(SwarmFrame, GrowsAtOnceFollowsTheCentreAndShrinksOnlyWhenClearlyTooLoose) {
  SwarmFrame frame;
  // GIVEN a swarm 20 m across: the frame fits it with a margin
  const SwarmFrame::Box first = frame.follow(scene({{0, 0}, {20, 0}, {10, 10}}));
  EXPECT_DOUBLE_EQ(first.cx_m, 10.0);
  EXPECT_DOUBLE_EQ(first.cy_m, 5.0);
  EXPECT_DOUBLE_EQ(first.half_m, 10.0 * 1.25 * 1.1);
  // WHEN it breathes in by 10 %: the scale holds, the centre follows
  const SwarmFrame::Box breathing = frame.follow(scene({{1, 0}, {19, 0}, {10, 9}}));
  EXPECT_DOUBLE_EQ(breathing.half_m, first.half_m);
  EXPECT_DOUBLE_EQ(breathing.cy_m, 4.5);
  // WHEN a UAV moves out: the frame grows at once, every UAV stays inside
  const SwarmFrame::Box grown = frame.follow(scene({{0, 0}, {40, 0}, {10, 10}}));
  EXPECT_GE(grown.half_m, 20.0 * 1.25);
  // WHEN the swarm closes to a third: the frame shrinks
  const SwarmFrame::Box shrunk = frame.follow(scene({{0, 0}, {10, 0}}));
  EXPECT_LT(shrunk.half_m, grown.half_m);
  EXPECT_GE(shrunk.half_m, 5.0 * 1.25);
  // AND a single UAV, or none with a position, still gets a readable frame
  EXPECT_GE(SwarmFrame().follow(scene({{3, 3}})).half_m, 5.0);
  EXPECT_GE(SwarmFrame().follow(scene({{kNan, 3}})).half_m, 5.0);
}

TEST(SwarmPicture, EachUavIsADotInThePaletteColourOfItsIdWithItsIdAndLinksAndCentresAreDrawn) {
  // GIVEN three UAVs, the agent of UAV 2 not answering, one link and one floating-frame centre
  SwarmScene s = scene({{0, 0}, {10, 0}, {5, 8}});
  s.uavs[2].agent_alive = false;
  s.links = {{0, 1}};
  s.centres = {{1, 2.0, -1.0}};
  SwarmFrame frame;
  // WHEN drawn
  const std::string svg = swarmSvg(s, frame.follow(s));
  // THEN there is a dot per UAV, coloured as the report colours series 0, 1, ...; grey for the silent agent
  const std::vector<std::string> dots = tags(svg, "circle", "marker");
  ASSERT_EQ(dots.size(), 3U);
  EXPECT_EQ(attribute(dots[0], "fill"), monitor::paletteColour(0));
  EXPECT_EQ(attribute(dots[1], "fill"), monitor::paletteColour(1));
  EXPECT_EQ(attribute(dots[2], "fill"), "#9e9e9e");
  // AND each dot is labelled with its UAV's id
  std::vector<std::string> labels;
  for (std::size_t pos = svg.find("class=\"point-label\""); pos != std::string::npos;
       pos = svg.find("class=\"point-label\"", pos + 1)) {
    const std::size_t begin = svg.find('>', pos) + 1;
    labels.push_back(svg.substr(begin, svg.find('<', begin) - begin));
  }
  EXPECT_EQ(labels, (std::vector<std::string>{"0", "1", "2"}));
  // AND the link is a line, the centre a cross in its agent's colour
  EXPECT_EQ(tags(svg, "polyline", "series").size(), 1U);
  const std::vector<std::string> crosses = tags(svg, "path", "marker");
  ASSERT_EQ(crosses.size(), 1U);
  EXPECT_EQ(attribute(crosses[0], "stroke"), monitor::paletteColour(1));
  // AND the axes carry the report's tick labels, in metres east and north
  EXPECT_FALSE(tags(svg, "text", "tick-x").empty());
  EXPECT_NE(svg.find("east [m]"), std::string::npos);
  EXPECT_NE(svg.find("north [m]"), std::string::npos);
  // AND the message carries the picture as it is
  const nlohmann::json j = nlohmann::json::parse(pictureJson(2.5, svg));
  EXPECT_EQ(j["svg"], svg);
  EXPECT_EQ(j["t_s"], 2.5);
}

monitor::TimeSeriesRow row(double t_s, double d_nb) {
  monitor::TimeSeriesRow r;
  r.t_s = t_s;
  r.d_nb_m = d_nb;
  r.drift_mps = 0.01;
  r.min_sep_m = 4.0;
  return r;
}

TEST(MetricWindow, KeepsTheLastWindowAndStartsAgainWhenTimeGoesBack) {
  MetricWindow window(60.0);
  for (int t = 0; t <= 100; ++t) window.add(row(t, 5.0));
  EXPECT_EQ(window.rows().front().t_s, 40.0);
  EXPECT_EQ(window.rows().back().t_s, 100.0);
  window.add(row(99.5, 5.0));  // re-ordered by less than a second: kept
  EXPECT_EQ(window.rows().size(), 62U);
  window.add(row(3.0, 5.0));  // a new run
  ASSERT_EQ(window.rows().size(), 1U);
  EXPECT_EQ(window.rows().front().t_s, 3.0);
  window.add(row(kNan, 5.0));
  EXPECT_EQ(window.rows().size(), 1U);
}

TEST(MetricPictures, AreTheReportsPlotsOverAWindowThatFillsFromTheLeftThenRolls) {
  monitor::MetricsConfig scoring;
  scoring.formation.radius_m = 5.0;
  scoring.radius_tolerance = 0.03;
  scoring.window_start_s = 10.0;
  MetricWindow window(60.0);
  for (int t = 0; t <= 20; ++t) window.add(row(t, 5.0 + 0.01 * t));
  // WHEN drawn after 20 s
  const std::vector<NamedPicture> early = metricPictures(window, scoring);
  // THEN the report's d_NB, drift and separation plots, in that order
  ASSERT_EQ(early.size(), 3U);
  EXPECT_EQ(early[0].name, "d_nb");
  EXPECT_EQ(early[1].name, "drift");
  EXPECT_EQ(early[2].name, "min_separation");
  // AND d_NB has the report's band r ± 3 % and the GNSS-loss line; separation the collision line
  EXPECT_EQ(tags(early[0].svg, "rect", "band").size(), 1U);
  EXPECT_NE(early[0].svg.find("GNSS lost"), std::string::npos);
  EXPECT_NE(early[2].svg.find("collision"), std::string::npos);
  // AND the time axis spans the whole minute from the first row: the last tick is at 60 s
  std::vector<std::string> ticks;
  for (const std::string& t : tags(early[0].svg, "text", "tick-x")) ticks.push_back(t);
  ASSERT_FALSE(ticks.empty());
  const std::size_t last = early[0].svg.rfind("class=\"tick-x\"");
  const std::size_t begin = early[0].svg.find('>', last) + 1;
  EXPECT_EQ(early[0].svg.substr(begin, early[0].svg.find('<', begin) - begin), "60");
  // WHEN 100 s are in: the axis has rolled to 40 .. 100 s
  for (int t = 21; t <= 100; ++t) window.add(row(t, 5.0));
  const std::string late = metricPictures(window, scoring)[0].svg;
  const std::size_t first = late.find("class=\"tick-x\"");
  const std::size_t first_begin = late.find('>', first) + 1;
  EXPECT_EQ(late.substr(first_begin, late.find('<', first_begin) - first_begin), "40");
  // AND the message lists them by name
  const nlohmann::json j = nlohmann::json::parse(picturesJson(100.0, early));
  ASSERT_EQ(j["plots"].size(), 3U);
  EXPECT_EQ(j["plots"][1]["name"], "drift");
}

}  // namespace
}  // namespace swa::live

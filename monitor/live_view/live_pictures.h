#pragma once
// The live page's pictures, drawn by the report's plot engine (svg_plot.h, report_html.h) so that the page and
// report.html share one tick rule, one palette and the same bands: the swarm from above at one truth sample, and the
// report's d_NB, drift and separation plots over the last minute of simulated time. The page only shows them. No I/O.
//
//   /swa/live/pictures/swarm    swa_live/Picture   {t_s, svg}: the swarm from above
//   /swa/live/pictures/metrics  swa_live/Pictures  {t_s, plots: [{name, svg}]}: d_nb, drift, min_separation

#include <deque>
#include <optional>
#include <string>
#include <vector>

#include "live_messages.h"
#include "swa/monitor/summary_format.h"
#include "swa/monitor/swarm_metrics.h"

namespace swa::live {

constexpr const char* kSwarmPictureTopic = "/swa/live/pictures/swarm";
constexpr const char* kMetricPicturesTopic = "/swa/live/pictures/metrics";
constexpr const char* kPictureSchemaName = "swa_live/Picture";
constexpr const char* kPicturesSchemaName = "swa_live/Pictures";
std::string pictureJsonSchema();
std::string picturesJsonSchema();

// The part of the world the swarm picture shows. It follows the UAVs' centre, grows at once when they spread and
// shrinks only when they use less than 70 % of it, so a breathing formation does not pump the zoom. An estimate
// that runs away does not shrink the swarm to a dot: only the UAVs are fitted, not the frame centres.
class SwarmFrame {
 public:
  struct Box {
    double cx_m = 0.0;
    double cy_m = 0.0;
    double half_m = 0.0;  // half the side of the square shown
  };
  Box follow(const SwarmScene& scene);

 private:
  Box box_;
  bool fitted_ = false;
};

// The swarm from above: neighbour links, each agent's floating-frame centre (a cross in its colour), each UAV (a dot
// in its colour with its id; grey while its agent does not answer). `box` is the part shown.
std::string swarmSvg(const SwarmScene& scene, const SwarmFrame::Box& box);
std::string pictureJson(double t_s, const std::string& svg);

// The metrics of the last window_s of simulated time, as the plots show them: a row more than a second older than
// the newest starts a new run (a replay, a restarted simulator) and clears the window.
class MetricWindow {
 public:
  explicit MetricWindow(double window_s = 60.0);
  void add(const monitor::TimeSeriesRow& row);
  const std::deque<monitor::TimeSeriesRow>& rows() const { return rows_; }
  double windowSeconds() const { return window_s_; }

 private:
  double window_s_;
  std::deque<monitor::TimeSeriesRow> rows_;
};

struct NamedPicture {
  std::string name;  // the report's plot name: d_nb, drift, min_separation
  std::string svg;
};
// The report's plots of d_NB, drift and minimum separation (same bands and lines, from `scoring`) over the window,
// the time axis a full window wide from its first row on, so that it fills from the left and then rolls.
std::vector<NamedPicture> metricPictures(const MetricWindow& window, const monitor::MetricsConfig& scoring);
std::string picturesJson(double t_s, const std::vector<NamedPicture>& pictures);

}  // namespace swa::live

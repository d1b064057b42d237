#include "live_pictures.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include <nlohmann/json.hpp>

#include "swa/monitor/report_html.h"
#include "swa/monitor/svg_plot.h"

namespace swa::live {
namespace {

using Json = nlohmann::ordered_json;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kMinHalf = 5.0;  // m: a single UAV or a tight cluster still shows some grid
constexpr double kMargin = 1.25;  // the UAVs' box × this, so dots and labels stay off the edge
constexpr double kSlack = 1.1;    // a new frame is this much larger than it must be: it need not grow at once again
constexpr double kShrinkBelow = 0.7;
constexpr const char* kDeadAgentColour = "#9e9e9e";
constexpr const char* kLinkColour = "#3c4858";

const std::string& uavColour(int id) { return monitor::paletteColour(static_cast<std::size_t>(std::max(id, 0))); }

Json pictureSchema(const char* title, const char* description, const Json& properties,
                   std::initializer_list<const char*> required) {
  Json names = Json::array();
  for (const char* r : required) names.push_back(r);
  return {{"title", title},
          {"description", description},
          {"type", "object"},
          {"properties", properties},
          {"required", names}};
}

}  // namespace

std::string pictureJsonSchema() {
  return pictureSchema(
             kPictureSchemaName, "the swarm from above as an SVG document, drawn by the monitor",
             {{"t_s", {{"type", "number"}, {"description", "simulated time [s]"}}}, {"svg", {{"type", "string"}}}},
             {"t_s", "svg"})
      .dump();
}

std::string picturesJsonSchema() {
  const Json plot = {{"type", "object"},
                     {"properties", {{"name", {{"type", "string"}}}, {"svg", {{"type", "string"}}}}},
                     {"required", {"name", "svg"}}};
  return pictureSchema(kPicturesSchemaName,
                       "the run report's plots over the last minute of simulated time, as SVG documents",
                       {{"t_s", {{"type", "number"}, {"description", "simulated time of the newest row [s]"}}},
                        {"plots", {{"type", "array"}, {"items", plot}}}},
                       {"t_s", "plots"})
      .dump();
}

SwarmFrame::Box SwarmFrame::follow(const SwarmScene& scene) {
  double min_x = std::numeric_limits<double>::infinity();
  double max_x = -min_x;
  double min_y = min_x;
  double max_y = -min_x;
  for (const SwarmScene::Uav& u : scene.uavs) {
    if (!std::isfinite(u.x_m) || !std::isfinite(u.y_m)) continue;
    min_x = std::min(min_x, u.x_m);
    max_x = std::max(max_x, u.x_m);
    min_y = std::min(min_y, u.y_m);
    max_y = std::max(max_y, u.y_m);
  }
  if (min_x > max_x) {
    if (!fitted_) box_ = {0.0, 0.0, kMinHalf * kSlack};
    return box_;
  }
  const double need = std::max(kMinHalf, 0.5 * std::max(max_x - min_x, max_y - min_y) * kMargin);
  if (!fitted_ || need > box_.half_m || need < kShrinkBelow * box_.half_m) box_.half_m = need * kSlack;
  box_.cx_m = 0.5 * (min_x + max_x);
  box_.cy_m = 0.5 * (min_y + max_y);
  fitted_ = true;
  return box_;
}

std::string swarmSvg(const SwarmScene& scene, const SwarmFrame::Box& box) {
  monitor::PlotSpec spec;
  spec.x_label = "east";
  spec.x_unit = "m";
  spec.y_label = "north";
  spec.y_unit = "m";
  spec.equal_aspect = true;
  spec.track_markers = false;
  spec.width_px = 560;
  spec.height_px = 520;
  spec.x_min = box.cx_m - box.half_m;
  spec.x_max = box.cx_m + box.half_m;
  spec.y_min = box.cy_m - box.half_m;
  spec.y_max = box.cy_m + box.half_m;

  std::map<int, const SwarmScene::Uav*> by_id;
  for (const SwarmScene::Uav& u : scene.uavs) by_id[u.id] = &u;
  monitor::PlotSeries links;
  links.colour = kLinkColour;
  links.opacity = 0.55;
  links.width_px = 1.0;
  for (const auto& [a, b] : scene.links) {
    const auto ua = by_id.find(a);
    const auto ub = by_id.find(b);
    if (ua == by_id.end() || ub == by_id.end()) continue;
    links.x.insert(links.x.end(), {ua->second->x_m, ub->second->x_m, kNaN});
    links.y.insert(links.y.end(), {ua->second->y_m, ub->second->y_m, kNaN});
  }
  spec.series.push_back(std::move(links));
  for (const SwarmScene::Centre& c : scene.centres) {
    monitor::PlotSeries centre;
    centre.marker = monitor::MarkerShape::kCross;
    centre.colour = uavColour(c.uav);
    centre.x = {c.x_m};
    centre.y = {c.y_m};
    spec.series.push_back(std::move(centre));
  }
  for (const SwarmScene::Uav& u : scene.uavs) {
    monitor::PlotSeries dot;
    dot.marker = monitor::MarkerShape::kDot;
    dot.marker_px = 6.0;
    dot.colour = u.agent_alive ? uavColour(u.id) : kDeadAgentColour;
    dot.x = {u.x_m};
    dot.y = {u.y_m};
    dot.point_labels = {std::to_string(u.id)};
    spec.series.push_back(std::move(dot));
  }
  return monitor::renderSvg(spec);
}

std::string pictureJson(double t_s, const std::string& svg) {
  return Json{{"t_s", std::isfinite(t_s) ? Json(t_s) : Json(nullptr)}, {"svg", svg}}.dump();
}

MetricWindow::MetricWindow(double window_s) : window_s_(window_s) {}

void MetricWindow::add(const monitor::TimeSeriesRow& row) {
  if (!std::isfinite(row.t_s)) return;
  if (!rows_.empty() && row.t_s < rows_.back().t_s - 1.0) rows_.clear();
  rows_.push_back(row);
  while (rows_.front().t_s < row.t_s - window_s_) rows_.pop_front();
}

std::vector<NamedPicture> metricPictures(const MetricWindow& window, const monitor::MetricsConfig& scoring) {
  monitor::RunReport run;
  run.series.assign(window.rows().begin(), window.rows().end());
  monitor::ReportNotes notes;
  notes.scoring = scoring;
  notes.gnss_loss_s = monitor::gnssLossTime(scoring);
  const double start = run.series.empty() ? 0.0 : run.series.front().t_s;
  std::vector<NamedPicture> pictures;
  for (monitor::ReportPlot& plot : monitor::reportTimePlots({run}, notes)) {
    if (plot.name != "d_nb" && plot.name != "drift" && plot.name != "min_separation") continue;
    plot.spec.x_min = start;
    plot.spec.x_max = start + window.windowSeconds();
    plot.spec.width_px = 560;
    plot.spec.height_px = 240;
    pictures.push_back({plot.name, monitor::renderSvg(plot.spec)});
  }
  return pictures;
}

std::string picturesJson(double t_s, const std::vector<NamedPicture>& pictures) {
  Json plots = Json::array();
  for (const NamedPicture& p : pictures) plots.push_back({{"name", p.name}, {"svg", p.svg}});
  return Json{{"t_s", std::isfinite(t_s) ? Json(t_s) : Json(nullptr)}, {"plots", plots}}.dump();
}

}  // namespace swa::live

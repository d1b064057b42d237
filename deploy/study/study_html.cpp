#include "study_html.h"

#include <cmath>
#include <map>
#include <optional>
#include <vector>

#include "swa/monitor/svg_plot.h"

namespace swa::study {
namespace {

struct Metric {
  const char* key;
  const char* label;
  const char* unit;
};
// What a study is usually about (DESIGN §5): cohesion, drift, safety, estimator consistency.
constexpr Metric kMetrics[] = {
    {"mean_neighbor_distance_m", "d_NB (final)", "m"},
    {"drift_velocity_mps", "drift velocity", "m/s"},
    {"min_separation_m", "minimum separation", "m"},
    {"collisions", "collisions", ""},
    {"formation_error_m", "formation error", "m"},
    {"anees_position", "ANEES (position)", ""},
};

std::optional<double> numberOf(const std::string& text) {
  try {
    std::size_t used = 0;
    const double v = std::stod(text, &used);
    if (used == text.size() && std::isfinite(v)) return v;
  } catch (const std::exception&) {
  }
  return std::nullopt;
}

double valueOf(const RunRow& run, const char* key) {
  for (const monitor::NamedValue& m : run.metrics) {
    if (m.key == key) return m.value;
  }
  return monitor::kNaN;
}

struct Stats {
  double mean = monitor::kNaN, std = monitor::kNaN;
};

// Mean and sample standard deviation of the finite values.
Stats stats(const std::vector<double>& values) {
  double sum = 0.0;
  int n = 0;
  for (const double v : values) {
    if (std::isfinite(v)) {
      sum += v;
      ++n;
    }
  }
  Stats s;
  if (n == 0) return s;
  s.mean = sum / n;
  double sq = 0.0;
  for (const double v : values) {
    if (std::isfinite(v)) sq += (v - s.mean) * (v - s.mean);
  }
  s.std = n > 1 ? std::sqrt(sq / (n - 1)) : 0.0;
  return s;
}

std::string plot(const StudyRecord& s, std::size_t axis, const Metric& metric) {
  const StudyPlan& plan = s.plan;
  const Axis& a = plan.axes[axis];
  bool numeric = true;
  for (const std::string& v : a.values) numeric = numeric && numberOf(v).has_value();
  // Values per grid point, then grouped by the other keys' values (the series) and this key's value (the x).
  std::map<std::size_t, std::vector<double>> by_point;
  for (const RunRow& r : s.runs) by_point[r.point].push_back(valueOf(r, metric.key));
  // One series per combination of the other keys' values, in the order the values were given (a point's index
  // along every other axis); each maps this key's value index to the stats there.
  struct Series {
    std::string label;
    std::map<std::size_t, Stats> points;
  };
  std::map<std::vector<std::size_t>, Series> series;
  for (const auto& [point, values] : by_point) {
    std::vector<std::size_t> index(plan.axes.size());
    std::size_t rest = point;
    for (std::size_t k = plan.axes.size(); k-- > 0;) {
      index[k] = rest % plan.axes[k].values.size();
      rest /= plan.axes[k].values.size();
    }
    const std::size_t x = index[axis];
    index[axis] = 0;
    Series& line = series[index];
    if (line.label.empty()) {
      for (std::size_t k = 0; k < plan.axes.size(); ++k) {
        if (k == axis) continue;
        line.label += (line.label.empty() ? "" : ", ") + plan.axes[k].key + "=" + plan.axes[k].values[index[k]];
      }
      if (line.label.empty()) line.label = metric.label;
    }
    line.points[x] = stats(values);
  }
  monitor::PlotSpec spec;
  spec.title = std::string(metric.label) + " against " + a.key;
  spec.x_label = a.key;
  spec.y_label = metric.label;
  spec.y_unit = metric.unit;
  spec.width_px = 640;
  spec.height_px = 300;
  std::size_t colour = 0;
  for (const auto& [index, one] : series) {
    const std::map<std::size_t, Stats>& points = one.points;
    monitor::PlotSeries mean;
    mean.label = one.label;
    mean.colour = monitor::paletteColour(colour);
    mean.width_px = 2.0;
    monitor::PlotSeries high;
    high.colour = mean.colour;
    high.dashed = true;
    high.width_px = 1.0;
    high.opacity = 0.5;
    monitor::PlotSeries low = high;
    for (const auto& [x, st] : points) {
      const double xv = numeric ? *numberOf(a.values[x]) : static_cast<double>(x);
      mean.x.push_back(xv);
      mean.y.push_back(st.mean);
      high.x.push_back(xv);
      high.y.push_back(st.mean + st.std);
      low.x.push_back(xv);
      low.y.push_back(st.mean - st.std);
    }
    spec.series.push_back(std::move(mean));
    spec.series.push_back(std::move(high));
    spec.series.push_back(std::move(low));
    ++colour;
  }
  std::string out = monitor::renderSvg(spec);
  if (!numeric) {
    out += "<p class=\"note\">" + monitor::escapeXml(a.key) + ": ";
    for (std::size_t j = 0; j < a.values.size(); ++j) {
      out += (j ? ", " : "") + std::to_string(j) + " = " + monitor::escapeXml(a.values[j]);
    }
    out += "</p>\n";
  }
  return out;
}

}  // namespace

std::string studyHtml(const StudyRecord& s) {
  std::string html = R"(<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><title>SWA study )" +
                     monitor::escapeXml(s.study_id) + R"(</title>
<style>body{font-family:sans-serif;margin:2em;color:#1d2430}h2{margin-top:2em}.note{color:#555;font-size:90%}
table{border-collapse:collapse}td,th{border:1px solid #ccc;padding:2px 8px;text-align:left}</style></head><body>
)";
  html += "<h1>SWA study " + monitor::escapeXml(s.study_id) + "</h1>\n<table>\n";
  html += "<tr><th>scenario</th><td>" + monitor::escapeXml(s.scenario) + "</td></tr>\n";
  html += "<tr><th>version</th><td>" + monitor::escapeXml(s.version) + "</td></tr>\n";
  for (const Axis& a : s.plan.axes) {
    std::string values;
    for (const std::string& v : a.values) values += (values.empty() ? "" : ", ") + v;
    html += "<tr><th>swept " + monitor::escapeXml(a.key) + "</th><td>" + monitor::escapeXml(values) + "</td></tr>\n";
  }
  html += "<tr><th>seeds</th><td>" + std::to_string(s.first_seed) + " .. " +
          std::to_string(s.first_seed + static_cast<std::uint64_t>(s.plan.seeds) - 1) + " (" +
          std::to_string(s.plan.seeds) + " per grid point, " + std::to_string(s.runs.size()) + " runs)</td></tr>\n";
  html += "</table>\n<p class=\"note\">Solid: the mean over the seeds at each value; dashed: mean ± one standard "
          "deviation. runs.csv has every run.</p>\n";
  for (std::size_t axis = 0; axis < s.plan.axes.size(); ++axis) {
    html += "<h2>Against " + monitor::escapeXml(s.plan.axes[axis].key) + "</h2>\n";
    for (const Metric& m : kMetrics) html += plot(s, axis, m);
  }
  html += "</body></html>\n";
  return html;
}

}  // namespace swa::study

#include "study_plots.h"

#include "study_plot_axis.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <tuple>
#include <utility>

#include "swa/params/error.h"
#include "swa/run_record/scoring.h"
#include "swa/sim/scenario_io.h"

namespace swa::study {
namespace {

using monitor::kNaN;

// DESIGN §5: the swarm's centroid averages N roughly independent drifts, so it drifts as N^-1/2.
constexpr double kDriftExponent = -0.5;
// Position NEES has 2 degrees of freedom (x, y): a consistent filter's ANEES is 2 on average, the run report's line.
constexpr double kPositionNeesDof = 2.0;
constexpr double kBandOpacity = 0.15;  // as the run report's bands
constexpr const char* kBandColour = "#2ca02c";
constexpr const char* kGuideColour = "#555555";
constexpr const char* kCollisionColour = "#d62728";
// One plot a row (two side by side do not fit a page); wide enough for a legend of "key = value" series labels.
constexpr int kPlotWidthPx = 760;
constexpr int kPlotHeightPx = 320;
constexpr double kMarkerPx = 4.5;  // smaller than the default 5: up to 4 series sit side by side at one value

// A band at value j of the axis, of series si's grid point there.
struct PointBand {
  std::size_t j;
  std::size_t si;
  double low;
  double high;
};

// The bands drawn, the simplest that is true: one across the plot when every grid point (`complete`: none lacks
// one) has the same; else one over each value's share of the axis when the series agree there; else one behind
// each series' marker (a band that changes with another key than the axis').
void addBands(monitor::PlotSpec& spec, const XAxis& x, std::size_t series_count, std::vector<PointBand> bands,
              bool complete, const std::string& label) {
  if (bands.empty()) return;
  const auto same_band = [](const PointBand& a, const PointBand& b) { return a.low == b.low && b.high == a.high; };
  const bool same = std::all_of(bands.begin(), bands.end(), [&](const PointBand& b) { return same_band(b, bands[0]); });
  if (same && complete) {
    spec.bands.push_back({bands.front().low, bands.front().high, label, kBandColour, kBandOpacity});
    return;
  }
  bool series_agree = true;
  for (const PointBand& a : bands) {
    for (const PointBand& b : bands) series_agree = series_agree && (a.j != b.j || same_band(a, b));
  }
  std::set<std::tuple<std::size_t, std::size_t, double, double>> drawn;  // value, series (or none), band: each once
  for (const PointBand& p : bands) {
    if (!drawn.insert({p.j, series_agree ? 0 : p.si, p.low, p.high}).second) continue;
    const auto [x_low, x_high] = series_agree ? extentOf(x, p.j) : slotOf(x, p.j, p.si, series_count);
    monitor::PlotBand b{p.low, p.high, spec.bands.empty() ? label : "", kBandColour, kBandOpacity};
    b.x_low = x_low;
    b.x_high = x_high;
    spec.bands.push_back(b);
  }
}

std::string percent(double fraction) { return monitor::formatFixed(100.0 * fraction, 1) + " %"; }
std::string metres(double value) { return monitor::formatFixed(value, 3) + " m"; }

// d_NB: the run report's PASS band, r ± tolerance of each grid point's scenario, and r when it is one.
void addRadiusBand(StudyPlot& plot, const StudyView& view, const XAxis& x, const std::vector<PointSeries>& series) {
  std::vector<PointBand> bands;
  std::vector<double> radii;
  std::size_t unknown = 0;
  double tolerance = kNaN;
  for (std::size_t si = 0; si < series.size(); ++si) {
    for (const auto& [j, point] : series[si].at) {
      const std::optional<monitor::MetricsConfig>& scoring = view.scoring_at[point];
      if (!scoring) {
        ++unknown;
        continue;
      }
      const double r = scoring->formation.radius_m;
      tolerance = scoring->radius_tolerance;
      bands.push_back({j, si, r * (1.0 - scoring->radius_tolerance), r * (1.0 + scoring->radius_tolerance)});
      radii.push_back(r);
    }
  }
  if (bands.empty()) {
    plot.notes.push_back("No r ± tolerance band: study.json cannot tell r of any grid point.");
    return;
  }
  addBands(plot.spec, x, series.size(), bands, unknown == 0, "r ± " + percent(tolerance));
  const bool one_r = std::all_of(radii.begin(), radii.end(), [&](double r) { return r == radii.front(); });
  if (one_r && unknown == 0) {
    plot.spec.lines.push_back(
        {monitor::LineOrientation::kHorizontal, radii.front(), "r = " + metres(radii.front()), kGuideColour, true});
  }
  plot.notes.push_back("Shaded: the formation radius r ± " + percent(tolerance) +
                       " of each grid point's scenario, the run report's PASS band for the final d_NB.");
  if (unknown > 0) {
    plot.notes.push_back(std::to_string(unknown) +
                         " grid point(s) have no band: they change formation.spacing_m without "
                         "agent.formation.radius_m, and r follows the spacing unless given.");
  }
}

// ANEES: each run's own chi-square band, as its report draws it (the monitor's aneesBand for the run's K agents),
// and the value a consistent filter has on average.
void addAneesBand(StudyPlot& plot, const StudyView& view, const XAxis& x, const std::vector<PointSeries>& series) {
  std::vector<PointBand> bands;
  bool complete = true;
  for (std::size_t si = 0; si < series.size(); ++si) {
    for (const auto& [j, point] : series[si].at) {
      const std::vector<double> lows = view.values(point, "anees_band_low");
      const std::vector<double> highs = view.values(point, "anees_band_high");
      bool any = false;
      for (std::size_t r = 0; r < lows.size(); ++r) {
        if (!std::isfinite(lows[r]) || !std::isfinite(highs[r])) continue;
        bands.push_back({j, si, lows[r], highs[r]});
        any = true;
      }
      complete = complete && any;
    }
  }
  double alpha = monitor::MetricsConfig{}.anees_alpha;
  for (const std::optional<monitor::MetricsConfig>& scoring : view.scoring_at) {
    if (scoring) alpha = scoring->anees_alpha;
  }
  addBands(plot.spec, x, series.size(), bands, complete, "χ² " + percent(1.0 - alpha) + " band of the runs");
  const bool one_band = plot.spec.bands.size() == 1 && std::isnan(plot.spec.bands.front().x_low);
  plot.spec.lines.push_back({monitor::LineOrientation::kHorizontal, kPositionNeesDof,
                             "expected " + monitor::formatFixed(kPositionNeesDof, 0), kGuideColour, true});
  plot.notes.push_back(
      bands.empty() ? "No run has an ANEES band (no evaluated agent in its window)."
                    : "Shaded: each run's two-sided chi-square acceptance band for a mean over its K agents of 2-dof "
                      "NEES (K·ANEES ~ χ²(2K)), as its run report draws it; a consistent filter's runs lie inside it, "
                      "around 2." +
                          std::string(one_band ? "" : " K differs between grid points: each has its own band."));
}

// The drift's N^-1/2 guide: through the mean of every run at the smallest N (all series), not fitted.
void addDriftGuide(StudyPlot& plot, const StudyView& view, const XAxis& x, std::size_t axis) {
  const auto smallest = std::min_element(x.at.begin(), x.at.end());
  const std::size_t j0 = static_cast<std::size_t>(smallest - x.at.begin());
  std::vector<double> at_smallest;
  for (std::size_t point = 0; point < view.runs_at.size(); ++point) {
    if (indexOf(view.study.plan, point)[axis] != j0) continue;
    for (const double v : view.values(point, "drift_velocity_mps")) at_smallest.push_back(v);
  }
  const Stats anchor = statsOf(at_smallest);
  if (!(anchor.mean > 0.0)) {
    plot.notes.push_back("No N^-1/2 guide: no positive mean drift at the smallest N to draw it through.");
    return;
  }
  std::vector<double> n = x.at;
  std::sort(n.begin(), n.end());
  monitor::PlotSeries guide;
  guide.label = "∝ N^-1/2";
  guide.colour = kGuideColour;
  guide.dash_pattern = "5 4";
  guide.width_px = 1.25;
  for (const double v : n) {
    guide.x.push_back(v);
    guide.y.push_back(anchor.mean * std::pow(v / *smallest, kDriftExponent));
  }
  plot.spec.series.push_back(std::move(guide));
  plot.notes.push_back(
      "Log-log axes. Dashed: a guide ∝ N^-1/2 (DESIGN §5's expected trend) drawn through the mean "
      "drift of all runs at N = " +
      x.axis->values[j0] + " (" + monitor::formatFixed(anchor.mean, 4) +
      " m/s); it is anchored there, not fitted: how the other sizes sit against it is the result.");
}

// The series' means ± standard deviations, each series its own colour, marker and dash.
void addSeries(monitor::PlotSpec& spec, const StudyView& view, const XAxis& x, const std::vector<PointSeries>& series,
               const StudyMetric& metric) {
  for (std::size_t si = 0; si < series.size(); ++si) {
    monitor::PlotSeries s;
    s.label = series[si].label;
    s.colour = monitor::paletteColour(si);
    s.marker = monitor::markerShape(si);
    s.marker_px = kMarkerPx;
    s.joined = x.numeric;  // nothing lies between two categories: their means are not joined
    s.dash_pattern = monitor::dashPattern(si);
    s.width_px = 1.75;
    for (const auto& [j, point] : series[si].at) {
      const Stats st = statsOf(view.values(point, metric.key));
      s.x.push_back(shiftedX(x, j, si, series.size()));
      s.y.push_back(st.mean);
      s.y_err.push_back(st.n > 1 ? st.std : kNaN);
    }
    spec.series.push_back(std::move(s));
  }
}

// Whether a point or error bar of the plot reaches above `value`.
bool anyAbove(const monitor::PlotSpec& spec, double value) {
  for (const monitor::PlotSeries& s : spec.series) {
    for (std::size_t i = 0; i < s.y.size(); ++i) {
      const double e = i < s.y_err.size() && std::isfinite(s.y_err[i]) ? s.y_err[i] : 0.0;
      if (s.y[i] + e > value) return true;
    }
  }
  return false;
}

}  // namespace

const std::vector<StudyMetric>& studyMetrics() {
  static const std::vector<StudyMetric> kMetrics{
      {"mean_neighbor_distance_m", "d_NB (final)", "m", MetricKind::kNeighbourDistance},
      {"drift_velocity_mps", "drift velocity", "m/s", MetricKind::kDrift},
      {"min_separation_m", "minimum separation", "m", MetricKind::kSeparation},
      {"collisions", "collisions", "", MetricKind::kCollisions},
      {"formation_error_m", "formation error", "m", MetricKind::kPlain},
      {"anees_position", "ANEES (position)", "", MetricKind::kAnees},
  };
  return kMetrics;
}

Stats statsOf(const std::vector<double>& values) {
  Stats s;
  double sum = 0.0;
  for (const double v : values) {
    if (!std::isfinite(v)) continue;
    sum += v;
    ++s.n;
  }
  if (s.n == 0) return s;
  s.mean = sum / static_cast<double>(s.n);
  double sq = 0.0;
  for (const double v : values) {
    if (std::isfinite(v)) sq += (v - s.mean) * (v - s.mean);
  }
  s.std = s.n > 1 ? std::sqrt(sq / static_cast<double>(s.n - 1)) : 0.0;
  return s;
}

namespace {

// How grid point `point`'s runs were scored, rebuilt from the recorded base scenario and the point's overrides.
std::optional<monitor::MetricsConfig> scoringOfPoint(const StudyRecord& study, std::size_t point) {
  const std::vector<std::string> overrides = pointOverrides(study.plan, point);
  bool spacing = false;
  bool radius = false;
  for (const std::string& o : overrides) {
    const std::string key = sim::canonicalScenarioKey(o.substr(0, o.find('=')));
    spacing = spacing || key == "formation.spacing_m";
    radius = radius || key == "agent.formation.radius_m";
  }
  // The recorded scenario gives r explicitly; the run's r followed its spacing unless the file gave r.
  if (spacing && !radius) return std::nullopt;
  try {
    return record::scoringOf(sim::parseRecordedScenario(study.scenario_yaml, "study.json", overrides)).metrics;
  } catch (const params::ConfigError&) {
    return std::nullopt;
  }
}

}  // namespace

StudyView::StudyView(const StudyRecord& s) : study(s) {
  const std::size_t points = pointCount(s.plan);
  runs_at.resize(points);
  for (const RunRow& r : s.runs) {
    if (r.point < points) runs_at[r.point].push_back(&r);
  }
  for (std::size_t point = 0; point < points; ++point) scoring_at.push_back(scoringOfPoint(s, point));
}

std::vector<double> StudyView::values(std::size_t point, const char* key) const {
  std::vector<double> out;
  for (const RunRow* r : runs_at[point]) {
    double v = kNaN;
    for (const monitor::NamedValue& m : r->metrics) {
      if (m.key == key) v = m.value;
    }
    out.push_back(v);
  }
  return out;
}

StudyPlot studyPlot(const StudyView& view, std::size_t axis, const StudyMetric& metric) {
  const StudyPlan& plan = view.study.plan;
  const XAxis x = xAxisOf(plan.axes[axis], metric.kind == MetricKind::kDrift);
  const std::vector<PointSeries> series = seriesAlong(plan, axis);
  StudyPlot plot;
  monitor::PlotSpec& spec = plot.spec;
  spec.title = std::string(metric.label) + " against " + x.axis->key;
  if (plan.axes.size() == 2) spec.title += ", by " + plan.axes[1 - axis].key;
  spec.y_label = metric.label;
  spec.y_unit = metric.unit;
  spec.width_px = kPlotWidthPx;
  spec.height_px = kPlotHeightPx;
  setXAxis(spec, x);
  addSeries(spec, view, x, series, metric);
  switch (metric.kind) {
    case MetricKind::kNeighbourDistance:
      addRadiusBand(plot, view, x, series);
      break;
    case MetricKind::kDrift:
      spec.y_log = x.log;
      spec.y_include_zero = !x.log;
      if (x.log && x.axis->key == "uav_count") {
        addDriftGuide(plot, view, x, axis);
      } else if (x.log) {
        plot.notes.push_back("Log-log axes: a power law is a straight line.");
      }
      break;
    case MetricKind::kSeparation: {
      double distance = monitor::MetricsConfig{}.collision_distance_m;
      for (const auto& scoring : view.scoring_at) {
        if (scoring) distance = scoring->collision_distance_m;
      }
      spec.y_include_zero = true;
      spec.lines.push_back(
          {monitor::LineOrientation::kHorizontal, distance, "collision " + metres(distance), kCollisionColour, true});
      break;
    }
    case MetricKind::kCollisions:
      // A count: the axis starts half a collision below 0 (so markers at 0 stay whole) and shows at least 0..1.
      spec.y_min = -0.5;
      if (!anyAbove(spec, 1.0)) spec.y_max = 1.0;
      spec.lines.push_back({monitor::LineOrientation::kHorizontal, 0.0, "none", kGuideColour, true});
      break;
    case MetricKind::kAnees:
      addAneesBand(plot, view, x, series);
      break;
    case MetricKind::kPlain:
      break;
  }
  return plot;
}

}  // namespace swa::study

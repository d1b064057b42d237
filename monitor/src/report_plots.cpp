// The report's plots (reportPlots, report_html.h): d_NB, drift, separation and NEES over time for every run, and one
// trajectory plot per run; and the trajectories they are drawn from (TrajectoryRecorder).
#include "swa/monitor/report_html.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>

#include "report_text.h"

namespace swa::monitor {
namespace {

constexpr const char* kBandColour = "#2ca02c";
constexpr const char* kLossColour = "#7f7f7f";
constexpr const char* kCollisionColour = "#d62728";
// The largest swarm whose trajectory plot lists each UAV in a legend (every shipped scenario has at most 16).
constexpr std::size_t kMaxLegendUavs = 16;

bool anyFinite(const std::vector<double>& v) {
  return std::any_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); });
}

// One series per run of the time-series column `field`; a run without a finite value says so in the legend.
std::vector<PlotSeries> runSeries(const std::vector<RunReport>& runs, double TimeSeriesRow::*field) {
  std::vector<PlotSeries> series;
  for (std::size_t r = 0; r < runs.size(); ++r) {
    PlotSeries s;
    s.colour = paletteColour(r);
    s.x.reserve(runs[r].series.size());
    s.y.reserve(runs[r].series.size());
    for (const TimeSeriesRow& row : runs[r].series) {
      s.x.push_back(row.t_s);
      s.y.push_back(row.*field);
    }
    s.label = runs[r].label + (anyFinite(s.y) ? "" : " (no data)");
    series.push_back(std::move(s));
  }
  return series;
}

PlotSpec timePlot(const std::string& title, const std::string& y_label, const std::string& y_unit,
                  const std::vector<RunReport>& runs, double TimeSeriesRow::*field, const ReportNotes& notes) {
  PlotSpec spec;
  spec.title = title;
  spec.x_label = "time";
  spec.x_unit = "s";
  spec.y_label = y_label;
  spec.y_unit = y_unit;
  spec.series = runSeries(runs, field);
  spec.width_px = 800;
  if (std::isfinite(notes.gnss_loss_s)) {
    spec.lines.push_back({LineOrientation::kVertical, notes.gnss_loss_s, "GNSS lost", kLossColour, true});
  }
  return spec;
}

ReportPlot neesPlot(const std::vector<RunReport>& runs, const ReportNotes& notes) {
  ReportPlot plot;
  plot.name = "nees_position";
  PlotSpec& spec = plot.spec;
  spec = timePlot("Position NEES and ANEES", "NEES", "", runs, &TimeSeriesRow::nees_pos, notes);
  // The per-step values are noisy: draw them faint, and on top the running ANEES (the time average the summary's
  // anees_position is, from the window start on).
  for (std::size_t r = 0; r < runs.size(); ++r) {
    PlotSeries& raw = spec.series[r];
    raw.opacity = 0.35;
    raw.width_px = 1.0;
    raw.label += anyFinite(raw.y) ? " per step" : "";
    if (!anyFinite(raw.y)) continue;
    const double start = runs[r].summary.window_start_s;
    PlotSeries running;
    running.label = runs[r].label + " ANEES";
    running.colour = raw.colour;
    running.width_px = 2.25;
    double sum = 0.0;
    int count = 0;
    for (const TimeSeriesRow& row : runs[r].series) {
      if ((!std::isfinite(start) || row.t_s >= start) && std::isfinite(row.nees_pos)) {
        sum += row.nees_pos;
        ++count;
      }
      running.x.push_back(row.t_s);
      running.y.push_back(count > 0 ? sum / static_cast<double>(count) : kNaN);
    }
    spec.series.push_back(std::move(running));
  }

  // The chi-square band of each run that has one; runs sharing a band draw it once.
  struct Band {
    double low;
    double high;
    int agents;
    std::vector<std::string> labels;
    std::size_t run;
  };
  std::vector<Band> bands;
  for (std::size_t r = 0; r < runs.size(); ++r) {
    const Summary& s = runs[r].summary;
    if (!std::isfinite(s.anees_band_low) || !std::isfinite(s.anees_band_high)) continue;
    auto same = std::find_if(bands.begin(), bands.end(), [&](const Band& b) {
      return b.low == s.anees_band_low && b.high == s.anees_band_high && b.agents == s.anees_agents;
    });
    if (same == bands.end()) {
      bands.push_back({s.anees_band_low, s.anees_band_high, s.anees_agents, {runs[r].label}, r});
    } else {
      same->labels.push_back(runs[r].label);
    }
  }
  double band_high = 0.0;
  for (const Band& b : bands) {
    std::string label = "χ² band, K = " + std::to_string(b.agents);
    std::string colour = kBandColour;
    if (bands.size() > 1) {
      std::string names;
      for (const std::string& n : b.labels) names += (names.empty() ? "" : ", ") + n;
      label += " (" + names + ")";
      colour = paletteColour(b.run);
    }
    spec.bands.push_back({b.low, b.high, label, colour, 0.15});
    band_high = std::max(band_high, b.high);
  }
  spec.lines.push_back(
      {LineOrientation::kHorizontal, notes.nees_dof, "expected " + formatFixed(notes.nees_dof, 3), "#333333", true});

  // NEES spikes by orders of magnitude when a filter diverges; cap the axis so the band stays readable.
  std::vector<double> values;
  for (const PlotSeries& s : spec.series) {
    for (const double v : s.y) {
      if (std::isfinite(v)) values.push_back(v);
    }
  }
  std::sort(values.begin(), values.end());
  double cap = std::max(1.5 * band_high, 2.0 * notes.nees_dof);
  if (!values.empty())
    cap = std::max(cap, values[static_cast<std::size_t>(0.98 * static_cast<double>(values.size() - 1))]);
  if (!std::isfinite(cap) || cap <= 0.0) cap = 1.0;
  cap = niceTicks(0.0, cap, spec.target_ticks).hi;
  spec.y_min = 0.0;
  spec.y_max = cap;
  const auto clipped = values.end() - std::upper_bound(values.begin(), values.end(), cap);

  plot.caption =
      "Faint: the per-step mean position NEES of the agents' focal estimates against the true floating "
      "frame. Bold: the running ANEES, the time average of the per-step values from the window start on "
      "(its last value is the summary's anees_position). Shaded: the two-sided chi-square acceptance band "
      "for a mean over K agents of 2-dof NEES; a consistent filter stays inside it, around the expected "
      "value.";
  if (clipped > 0) {
    plot.caption += " " + std::to_string(clipped) + " value(s) above " + formatFixed(cap, 3) + " are clipped.";
  }
  if (bands.empty()) plot.caption += " No run has an ANEES band (no evaluated agent in the window).";
  return plot;
}

// A mission's planned path from where the run's centroid was at its start, and the centroid's own path: both empty
// without a mission or before it started.
void addMissionPaths(const RunReport& run, const MetricsConfig& scoring, PlotSpec& spec) {
  if (scoring.mission_legs.empty()) return;
  const auto start = std::find_if(run.series.begin(), run.series.end(), [&](const TimeSeriesRow& r) {
    return r.t_s >= scoring.mission_start_s && std::isfinite(r.centroid_x_m) && std::isfinite(r.centroid_y_m);
  });
  if (start == run.series.end()) return;
  PlotSeries centroid;
  centroid.label = "swarm centroid";
  centroid.colour = "#000000";
  centroid.width_px = 2.0;
  for (const TimeSeriesRow& r : run.series) {
    centroid.x.push_back(r.centroid_x_m);
    centroid.y.push_back(r.centroid_y_m);
  }
  PlotSeries planned;
  planned.label = "planned path";
  planned.colour = "#d62728";
  planned.dash_pattern = "6 4";
  planned.width_px = 2.0;
  const agent::MissionPlan plan(scoring.mission_legs);
  for (const agent::Vec2& w : plan.waypoints()) {
    planned.x.push_back(start->centroid_x_m + w.x());
    planned.y.push_back(start->centroid_y_m + w.y());
  }
  spec.series.push_back(std::move(centroid));
  spec.series.push_back(std::move(planned));
}

ReportPlot trajectoryPlot(const RunReport& run, const MetricsConfig& scoring, const std::string& name) {
  ReportPlot plot;
  plot.name = name;
  PlotSpec& spec = plot.spec;
  spec.title = "Top-down trajectories — " + run.label;
  spec.x_label = "x";
  spec.x_unit = "m";
  spec.y_label = "y";
  spec.y_unit = "m";
  spec.equal_aspect = true;
  spec.width_px = 560;
  spec.height_px = 480;
  // Past kMaxLegendUavs a legend would be taller than the plot (128 UAVs: 2384 px, the plot squeezed into its
  // top): each track's end is labelled with its UAV's id instead.
  const bool legend = run.trajectories.size() <= kMaxLegendUavs;
  PlotSeries ends;
  ends.colour = "#333333";
  ends.marker = MarkerShape::kDot;
  ends.marker_px = 1.5;
  for (const UavTrajectory& t : run.trajectories) {
    PlotSeries s;
    if (legend) s.label = "UAV " + std::to_string(t.id);
    if (!legend && !t.points.empty()) {
      ends.x.push_back(t.points.back().x_m);
      ends.y.push_back(t.points.back().y_m);
      ends.point_labels.push_back(std::to_string(t.id));
    }
    s.width_px = 1.25;
    s.x.reserve(t.points.size());
    s.y.reserve(t.points.size());
    for (const TrajectoryPoint& p : t.points) {
      s.x.push_back(p.x_m);
      s.y.push_back(p.y_m);
    }
    spec.series.push_back(std::move(s));
  }
  if (!legend) spec.series.push_back(std::move(ends));
  const std::size_t before = spec.series.size();
  addMissionPaths(run, scoring, spec);
  const bool mission = spec.series.size() > before;
  plot.caption =
      "World frame seen from above, equal scale on both axes; a hollow circle marks where each UAV's "
      "track starts, a filled square where it ends" +
      std::string(legend ? "" : ", labelled with the UAV's id") + " (" + std::to_string(run.trajectories.size()) +
      " UAVs; each run's plot has its own scale)." +
      std::string(mission ? " The dashed line is the mission's planned path from where the swarm's centroid was when "
                            "it started; the thick line is the centroid's own path."
                          : "");
  return plot;
}

}  // namespace

TrajectoryRecorder::TrajectoryRecorder(double period_s) : period_s_(period_s) {
  if (!std::isfinite(period_s) || period_s < 0.0) {
    throw std::invalid_argument("TrajectoryRecorder: period_s must be finite and >= 0");
  }
}

void TrajectoryRecorder::add(double t_s, const std::vector<UavTruth>& uavs) {
  const bool record = !any_recorded_ || t_s - last_recorded_s_ >= period_s_;
  std::set<int> present;
  for (const UavTruth& u : uavs) {
    if (!isPresent(u)) continue;
    present.insert(u.id);
    Track& track = tracks_[u.id];
    track.last_seen = {t_s, u.position_m.x(), u.position_m.y()};
    track.has_last_seen = true;
    if (record) track.points.push_back(track.last_seen);
  }
  if (!record) return;
  for (auto& [id, track] : tracks_) {
    if (present.count(id) != 0 || track.points.empty() || std::isnan(track.points.back().x_m)) continue;
    // Gone since the last recorded step: keep where it was last seen, then break the line.
    if (track.has_last_seen && track.last_seen.t_s > track.points.back().t_s) track.points.push_back(track.last_seen);
    track.points.push_back({t_s, kNaN, kNaN});
  }
  any_recorded_ = true;
  last_recorded_s_ = t_s;
}

std::vector<UavTrajectory> TrajectoryRecorder::trajectories() const {
  std::vector<UavTrajectory> out;
  for (const auto& [id, track] : tracks_) {
    UavTrajectory t{id, track.points};
    if (track.has_last_seen && (t.points.empty() || track.last_seen.t_s > t.points.back().t_s)) {
      t.points.push_back(track.last_seen);
    }
    out.push_back(std::move(t));
  }
  return out;
}

double gnssLossTime(const MetricsConfig& scoring) {
  return scoring.window_start_s > 0.0 ? scoring.window_start_s : kNaN;
}

std::vector<ReportPlot> reportTimePlots(const std::vector<RunReport>& runs, const ReportNotes& notes) {
  std::vector<ReportPlot> plots;
  const double r = notes.scoring.formation.radius_m;
  const double tolerance = notes.scoring.radius_tolerance;

  ReportPlot d_nb{"d_nb", "",
                  timePlot("Mean neighbour distance d_NB", "d_NB", "m", runs, &TimeSeriesRow::d_nb_m, notes)};
  d_nb.spec.bands.push_back(
      {r * (1.0 - tolerance), r * (1.0 + tolerance), "r ± " + percentText(tolerance), kBandColour, 0.15});
  d_nb.spec.lines.push_back({LineOrientation::kHorizontal, r, "r = " + metresText(r), "#333333", true});
  d_nb.caption =
      "Each UAV's mean distance to its nearest neighbours, averaged over the swarm. Shaded: the "
      "formation radius r ± " +
      percentText(tolerance) + ".";
  plots.push_back(std::move(d_nb));

  ReportPlot drift{"drift", "",
                   timePlot("Swarm drift velocity", "centroid speed", "m/s", runs, &TimeSeriesRow::drift_mps, notes)};
  drift.spec.y_include_zero = true;
  drift.caption =
      "Speed of the swarm centroid over the last drift window (time series drift_mps). The summary's "
      "drift_velocity_mps is the net centroid displacement over the whole window divided by its length.";
  plots.push_back(std::move(drift));

  ReportPlot separation{"min_separation", "",
                        timePlot("Minimum separation", "closest pair", "m", runs, &TimeSeriesRow::min_sep_m, notes)};
  separation.spec.y_include_zero = true;
  separation.spec.lines.push_back({LineOrientation::kHorizontal, notes.scoring.collision_distance_m,
                                   "collision " + metresText(notes.scoring.collision_distance_m), kCollisionColour,
                                   true});
  separation.caption = "Smallest distance between any two UAVs; below the red line a pair is in collision.";
  plots.push_back(std::move(separation));

  plots.push_back(neesPlot(runs, notes));

  // Stacked time plots line up: every one gets the widest legend.
  double legend = 0.0;
  for (const ReportPlot& p : plots) legend = std::max(legend, layoutPlot(p.spec).legend_px);
  for (ReportPlot& p : plots) p.spec.legend_width_px = legend;
  return plots;
}

std::vector<ReportPlot> reportPlots(const std::vector<RunReport>& runs, const ReportNotes& notes) {
  std::vector<ReportPlot> plots = reportTimePlots(runs, notes);
  std::set<std::string> names;
  for (const ReportPlot& p : plots) names.insert(p.name);
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const std::string base = "trajectories_" + reportFileStem(runs[i].label, i);
    std::string name = base;
    for (int k = 2; names.count(name) != 0; ++k) name = base + "_" + std::to_string(k);
    names.insert(name);
    plots.push_back(trajectoryPlot(runs[i], notes.scoring, name));
  }
  return plots;
}

}  // namespace swa::monitor

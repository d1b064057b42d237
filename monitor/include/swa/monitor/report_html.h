#pragma once
// The monitor's human-readable report: a self-contained report.html (inline SVG plots, a small style sheet, no
// script, no external resource) for one run or several runs side by side (e.g. "swa" and "standalone" on the same
// seed), and the same plots as separate .svg files.
//
// Contents, what a reader comes for first (issue #30): each run's verdict, then the plots: d_NB over time of every run
// with the r ± tolerance band, drift velocity, minimum separation with the collision distance, position NEES per
// step and the running ANEES with the chi-square band of each run, and one top-down trajectory plot per run; then
// notes (scenario, seeds, version, free-form extras), a summary table with one column per run and one row per
// summaryFields() key (plus the verdicts), and the caller's tables (events, restarts, ...). Each run keeps its
// palette colour in every time plot. All text is HTML-escaped. Output is deterministic (no clock, no locale).

#include <cstdint>
#include <limits>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "swa/monitor/accumulator.h"
#include "swa/monitor/summary_format.h"
#include "swa/monitor/svg_plot.h"
#include "swa/monitor/swarm_metrics.h"

namespace swa::monitor {

struct TrajectoryPoint {
  double t_s = 0.0;
  double x_m = kNaN;  // world frame; a NaN point is a gap (the UAV was absent), the line breaks there
  double y_m = kNaN;
};

struct UavTrajectory {
  int id = 0;
  std::vector<TrajectoryPoint> points;  // in time order, already decimated
};

// Decimates ground truth into UavTrajectory for the report: one point per UAV at the first step, then at the first
// step at least period_s after the previous recorded one. A UAV absent (isPresent() false, or missing) at a
// recorded step gets one NaN point, so its line breaks; its last present position is always kept, so the end
// marker is where the UAV really was last.
class TrajectoryRecorder {
 public:
  // Throws std::invalid_argument unless period_s is finite and >= 0 (0 keeps every step).
  explicit TrajectoryRecorder(double period_s = 0.5);

  void add(double t_s, const std::vector<UavTruth>& uavs);
  std::vector<UavTrajectory> trajectories() const;  // ascending id

 private:
  struct Track {
    std::vector<TrajectoryPoint> points;
    TrajectoryPoint last_seen;  // latest present position, recorded or not
    bool has_last_seen = false;
  };
  double period_s_;
  bool any_recorded_ = false;
  double last_recorded_s_ = 0.0;
  std::map<int, Track> tracks_;
};

struct RunReport {
  std::string label;  // column and legend name, e.g. "swa", "standalone"
  Summary summary;
  std::vector<TimeSeriesRow> series;  // in time order
  std::vector<UavTrajectory> trajectories;
  std::string verdict;  // free text shown under the run's name, e.g. "PASS: d_NB within 3 % of r"
};

// A table of text shown in its own section after the summary, e.g. the scenario events or the agent restarts of a
// run. Cells are plain text (escaped when rendered); a row shorter than `columns` is padded with empty cells.
struct ReportTable {
  std::string id;     // section id, reduced to [A-Za-z0-9_-] ("table-<id>")
  std::string title;  // section heading
  std::string note;   // paragraph under the heading (e.g. what the times mean); empty: none
  std::vector<std::string> columns;
  std::vector<std::vector<std::string>> rows;
  std::string empty_text = "None.";  // shown instead of the table when there is no row
};

struct ReportNotes {
  std::string title = "SWA swarm report";
  std::string scenario;
  std::vector<std::uint64_t> seeds;
  std::string version;
  // r and its band on the d_NB plot, the collision distance on the minimum separation plot (the runs' scoring)
  MetricsConfig scoring;
  double nees_dof = 2.0;                                          // expected NEES (reference line on the NEES plot)
  double gnss_loss_s = std::numeric_limits<double>::quiet_NaN();  // vertical line on the time plots (NaN: none)
  std::vector<std::pair<std::string, std::string>> extra;         // further notes, "key: value", in this order
  std::vector<ReportTable> tables;                                // sections after the summary, in this order
};

struct ReportPlot {
  std::string name;     // file stem, e.g. "d_nb", "trajectories_swa" (label reduced to [A-Za-z0-9_-])
  std::string caption;  // plain text (escaped when rendered)
  PlotSpec spec;
};

// The plots of the report, in report order: d_nb, drift, min_separation, nees_position, then trajectories_<label>
// per run. Names are unique (a repeated label gets a numeric suffix).
std::vector<ReportPlot> reportPlots(const std::vector<RunReport>& runs, const ReportNotes& notes);
// Only the plots over time (d_nb, drift, min_separation, nees_position), their legends of one width: what the live
// view draws of the last minute.
std::vector<ReportPlot> reportTimePlots(const std::vector<RunReport>& runs, const ReportNotes& notes);

// When GNSS was lost in a run scored with `scoring` (its window start; NaN when the window starts at 0): the
// vertical line on the time plots.
double gnssLossTime(const MetricsConfig& scoring);

// Table cell text of a summary value: "—" when not finite, an integer without decimals, else 5 significant digits
// (locale-independent).
std::string formatReportValue(double value);

// The whole report.html document.
std::string renderReportHtml(const std::vector<RunReport>& runs, const ReportNotes& notes);

// Creates `directory` if needed and writes report.html and <name>.svg for every reportPlots() entry. Returns the
// paths written, report.html first. Throws std::runtime_error when a file cannot be written.
std::vector<std::string> writeReport(const std::string& directory, const std::vector<RunReport>& runs,
                                     const ReportNotes& notes);

}  // namespace swa::monitor

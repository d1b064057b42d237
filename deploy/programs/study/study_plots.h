#pragma once
// The plots of study.html (study_html.h): one key metric against one swept key, at every value of that key the mean
// over the seeds (a marker) ± one standard deviation (a bar), one series per combination of the other swept keys'
// values, each with its own colour, marker shape and dash. How a plot is drawn follows from what it shows:
//
//   - a key whose values are all numbers is a numeric axis, the means joined by a line; any other key (and the
//     variants) is categorical: its names as the ticks, the markers not joined (there is nothing between two
//     categories); the series at one value sit side by side, a little apart, so equal values stay visible;
//   - the drift velocity against a positive numeric key spanning at least a factor 4 is on log-log axes (a power
//     law is a straight line); against uav_count with a dashed N^-1/2 guide through the mean at the smallest N
//     (DESIGN §5 expects that trend; the guide is anchored there, not fitted);
//   - d_NB has the run report's PASS band r ± tolerance of each grid point's scenario, the ANEES each run's own
//     chi-square band (as its report draws it) and the expected value 2, the minimum separation the collision
//     distance and the collisions the line at 0.
//
// Deterministic (the same study gives the same text); every text escaped.

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "study_record.h"
#include "swa/monitor/svg_plot.h"
#include "swa/monitor/swarm_metrics.h"

namespace swa::study {

enum class MetricKind : unsigned char { kPlain, kNeighbourDistance, kDrift, kSeparation, kCollisions, kAnees };

struct StudyMetric {
  const char* key;  // monitor::summaryFields key
  const char* label;
  const char* unit;
  MetricKind kind;
};

// The metrics study.html shows, in order: what a study is usually about (DESIGN §5): cohesion, drift, safety,
// estimator consistency.
const std::vector<StudyMetric>& studyMetrics();

// Mean, sample standard deviation (0 for one value) and count of the finite values; NaN mean without any.
struct Stats {
  double mean = monitor::kNaN;
  double std = monitor::kNaN;
  std::size_t n = 0;
};
Stats statsOf(const std::vector<double>& values);

// What the page needs of a study, worked out once: each grid point's runs and its scoring.
struct StudyView {
  explicit StudyView(const StudyRecord& study);
  const StudyRecord& study;
  std::vector<std::vector<const RunRow*>> runs_at;  // per grid point, in run order
  // Per grid point: how its runs were scored (record::scoringOf of its scenario: r, the PASS tolerance, the collision
  // distance). Empty when its scenario cannot be rebuilt from study.json: it failed to parse, or the point moves
  // formation.spacing_m without agent.formation.radius_m (r follows the spacing unless given, which the recorded
  // scenario no longer tells).
  std::vector<std::optional<monitor::MetricsConfig>> scoring_at;
  // The values of `key` of grid point `point`'s runs.
  std::vector<double> values(std::size_t point, const char* key) const;
};

// A plot and what a reader needs to know to read it (its notes, plain text).
struct StudyPlot {
  monitor::PlotSpec spec;
  std::vector<std::string> notes;
};

// `metric` against the plan's axis `axis`.
StudyPlot studyPlot(const StudyView& view, std::size_t axis, const StudyMetric& metric);

}  // namespace swa::study

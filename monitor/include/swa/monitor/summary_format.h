#pragma once
// Summary formats: a time-series CSV row, a flat key/value view of a Summary (the single list every writer and the
// seed aggregate iterate, so a new field cannot be forgotten in one of them), JSON writers, and the aggregate of
// many runs. Numbers are written in the shortest form that reads back to the same double, independent of the
// locale; a non-finite value is "nan" in CSV and null in JSON.

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "swa/monitor/accumulator.h"

namespace swa::monitor {

struct TimeSeriesRow {
  double t_s = 0.0;
  double d_nb_m = kNaN;
  double centroid_x_m = kNaN;
  double centroid_y_m = kNaN;
  double drift_mps = kNaN;
  double min_sep_m = kNaN;
  std::uint64_t collisions = 0;
  double spread_m = kNaN;
  int groups = 0;
  double formation_error_m = kNaN;
  double nees_pos = kNaN;
  double nees_vel = kNaN;
};

TimeSeriesRow toRow(const StepMetrics& step);

// "t_s,d_nb_m,centroid_x_m,centroid_y_m,drift_mps,min_sep_m,collisions,spread_m,groups,formation_error_m,nees_pos,
// nees_vel" (one line, no newline).
const std::string& csvHeader();
// The row's fields in header order, comma separated, no newline.
std::string formatCsvRow(const TimeSeriesRow& row);

// Shortest round-trip decimal form of a double ("3", "0.1", "1e+300"); "nan" / "inf" / "-inf" when not finite.
std::string formatNumber(double value);

struct NamedValue {
  std::string key;
  double value;
};

// Every Summary field, in declaration order, under its field name.
std::vector<NamedValue> summaryFields(const Summary& summary);

// The inverse of summaryFields, for reading a summary back (e.g. from a run's summary.json): every key of
// summaryFields found in `fields` sets its field; keys not found keep the default of Summary{}, unknown keys are
// ignored. A count field (steps, collisions, ...) takes a finite value rounded to the nearest integer (negative
// values clamp to 0 for unsigned counts) and keeps its default for NaN.
Summary summaryFromFields(const std::vector<NamedValue>& fields);

// Statistics of one key over the runs where it is finite (count of them in `runs`). std is the sample standard
// deviation (n - 1); 0 for a single run. All NaN when no run has a finite value.
struct Statistic {
  std::string key;
  int runs = 0;
  double mean = kNaN;
  double std = kNaN;
  double min = kNaN;
  double max = kNaN;
};

struct Aggregate {
  int runs = 0;
  std::vector<Statistic> metrics;                     // in order of first appearance of the key
  const Statistic* find(std::string_view key) const;  // nullptr when absent
};

// Keys are matched by name; a key missing from a run is treated like a NaN value in that run.
Aggregate aggregate(const std::vector<std::vector<NamedValue>>& runs);
Aggregate aggregate(const std::vector<Summary>& runs);

}  // namespace swa::monitor

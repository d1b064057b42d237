#pragma once
// Internal to study.html's plots (study_plots.cpp): where a study plot puts things along its x axis. A swept key's
// values are numbers (on a log axis when asked and wide enough) or categories at 0, 1, ...; the grid points form one
// series per combination of the other keys' values; at one value the series sit side by side, each in its own slot,
// so that a band can be drawn behind the markers it belongs to.

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "study_plan.h"
#include "swa/monitor/svg_plot.h"

namespace swa::study {

// How a swept key is drawn: where each of its values sits on the x axis.
struct XAxis {
  const Axis* axis = nullptr;
  bool numeric = true;
  bool log = false;
  std::vector<double> at;  // value j's position: the number, or j for a category
};

// Where `a`'s values sit; with `log_if_wide`, a positive numeric key spanning at least a factor 4 is a log axis.
XAxis xAxisOf(const Axis& a, bool log_if_wide);

// Where series `si` of `count` draws value j: beside the other series, the group centred on the value.
double shiftedX(const XAxis& x, std::size_t j, std::size_t si, std::size_t count);

// Series `si`'s slot at value j: its marker's column, half a step either side.
std::pair<double, double> slotOf(const XAxis& x, std::size_t j, std::size_t si, std::size_t count);

// Value j's share of the x axis: halfway (on the axis' scale) to its neighbours; NaN where it has none (the edge).
std::pair<double, double> extentOf(const XAxis& x, std::size_t j);

// Every grid point's index along each axis (the first axis varies slowest).
std::vector<std::size_t> indexOf(const StudyPlan& plan, std::size_t point);

// The grid points of one series: the other keys fixed, (value index along the axis, grid point) in value order.
struct PointSeries {
  std::string label;
  std::vector<std::pair<std::size_t, std::size_t>> at;
};

// One series per combination of the other keys' values, in the order the values were given.
std::vector<PointSeries> seriesAlong(const StudyPlan& plan, std::size_t axis);

// The x axis: the categories' names at 0, 1, ...; a log axis' ticks at the values themselves.
void setXAxis(monitor::PlotSpec& spec, const XAxis& x);

}  // namespace swa::study

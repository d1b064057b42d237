#pragma once
// Internal to the SVG plots: what svg_layout.cpp works out before anything is drawn (layoutPlot, svg_plot.h) and
// svg_plot.cpp needs again while drawing: which values an axis can show, the legend's rows, and which points of a long
// series are worth drawing.

#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

#include "swa/monitor/svg_plot.h"

namespace swa::monitor::svg {

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
constexpr double kLegendGap = 16.0;
constexpr double kLegendRow = 18.0;

// Whether `v` can sit on an axis (finite, and positive on a log one).
inline bool onAxis(double v, bool log) { return std::isfinite(v) && (!log || v > 0.0); }

// Indices of the points of one finite run [begin, end) that are drawn.
std::vector<std::size_t> thin(const std::vector<double>& sx, const std::vector<double>& sy, std::size_t begin,
                              std::size_t end);

}  // namespace swa::monitor::svg

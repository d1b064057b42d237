#pragma once
// Internal to the SVG plots (svg_layout.cpp, svg_plot.cpp): pixel numbers, and what the legend lists and how each
// entry's swatch is drawn, so the swatch and the plotted element always look alike.

#include <cstddef>
#include <string>
#include <vector>

#include "swa/monitor/svg_plot.h"

namespace swa::monitor::svg {

constexpr double kCoordLimit = 1e6;  // pixel coordinates are clamped to this (a clipped far-away point stays short)
constexpr double kLegendSwatch = 24.0;

std::string px(double v);                                // a pixel coordinate, clamped, 2 decimals
std::string dashAttr(bool dashed, const char* pattern);  // " stroke-dasharray=..." or ""

enum class LegendKind : unsigned char { kSeries, kBand, kLine, kStart, kEnd };

struct LegendEntry {
  LegendKind kind;
  std::string label;
  std::string colour;
  bool dashed = false;
  double opacity = 1.0;
  MarkerShape marker = MarkerShape::kNone;  // kSeries: a marker series' swatch is its marker
  std::string dash = "";                    // kSeries: its own dash pattern (PlotSeries::dash_pattern)
  bool joined = false;  // kSeries: a marker series joined by a line: the swatch is the line with the marker on it
};

// A series without a colour of its own takes the palette's; past the palette's 10 colours it is dashed.
std::string seriesColour(const PlotSeries& s, std::size_t index);
bool seriesDashed(const PlotSeries& s, std::size_t index);
// The labelled series, bands and lines, then the trajectory markers of an equal-aspect plot.
std::vector<LegendEntry> legendEntries(const PlotSpec& spec);
void renderLegendSwatch(std::string& out, const LegendEntry& e, double x, double y);

}  // namespace swa::monitor::svg

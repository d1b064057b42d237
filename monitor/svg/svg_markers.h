#pragma once
// Internal to the SVG plots (svg_plot.cpp): what is drawn point by point rather than as a line, a marker series'
// markers and labels, and the start and end of every track in XY mode.

#include <cstddef>
#include <string>

#include "swa/monitor/svg_plot.h"

namespace swa::monitor::svg {

// Appends a marker (and its label, if any) for every finite point of `s`, series number `index`. Returns whether
// there was one.
bool renderMarkers(std::string& out, const PlotSeries& s, std::size_t index, const PlotLayout& l);

// Appends the start and end markers of every line series of an XY plot.
void renderTrackMarkers(std::string& out, const PlotSpec& spec, const PlotLayout& l);

// One marker at (x, y) pixels, as the series and its legend swatch draw it.
void renderMarker(std::string& out, MarkerShape shape, double x, double y, double radius, const std::string& colour,
                  const std::string& attributes);

}  // namespace swa::monitor::svg

#include "swa/monitor/svg_plot.h"

#include "svg_layout.h"
#include "svg_legend.h"
#include "svg_markers.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

namespace swa::monitor {
namespace {

using namespace svg;

std::string axisTitle(const std::string& label, const std::string& unit) {
  if (unit.empty()) return label;
  if (label.empty()) return "[" + unit + "]";
  return label + " [" + unit + "]";
}

// The text of tick i of `t`, escaped.
std::string tickText(const AxisTicks& t, std::size_t i) {
  return i < t.labels.size() ? escapeXml(t.labels[i]) : formatTick(t.values[i], t);
}

// The stroke-dasharray of a line series: its own pattern, or the default dash when dashed.
std::string seriesDash(const PlotSeries& s, std::size_t index) {
  if (!s.dash_pattern.empty()) return " stroke-dasharray=\"" + escapeXml(s.dash_pattern) + "\"";
  return dashAttr(seriesDashed(s, index), "6 4");
}

// Every error bar of series `index`: a vertical stroke with short caps, in the series' colour.
void renderErrorBars(std::string& out, const PlotSeries& s, std::size_t index, const PlotLayout& l) {
  constexpr double kCapHalfWidth = 4.0;  // px: wide enough to see, narrower than the markers are apart
  const std::string colour = escapeXml(seriesColour(s, index));
  for (std::size_t i = 0; i < s.y_err.size(); ++i) {
    const double e = s.y_err[i];
    if (!(e > 0.0) || !std::isfinite(e) || !l.plottable(s.x[i], s.y[i])) continue;
    const double x = l.xToPx(s.x[i]);
    const double top = l.yToPx(s.y[i] + e);
    const double low = s.y[i] - e;
    // Below what a log axis shows: down to the plot's bottom edge (and no cap there, as the bar goes on).
    const bool cut = !l.plottable(s.x[i], low);
    const double bottom = cut ? l.bottom_px : l.yToPx(low);
    std::string d = "M" + px(x) + " " + px(top) + "V" + px(bottom) + "M" + px(x - kCapHalfWidth) + " " + px(top) + "H" +
                    px(x + kCapHalfWidth);
    if (!cut) d += "M" + px(x - kCapHalfWidth) + " " + px(bottom) + "H" + px(x + kCapHalfWidth);
    out += "<path class=\"error-bar\" data-series=\"" + std::to_string(index) + "\" d=\"" + d +
           "\" fill=\"none\" stroke=\"" + colour + "\" stroke-width=\"1.25\"/>\n";
  }
}

// The <svg> element's start, its white background and the title.
void renderBackground(std::string& out, const PlotSpec& spec, const PlotLayout& l) {
  out += "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + px(l.width_px) + "\" height=\"" + px(l.height_px) +
         "\" viewBox=\"0 0 " + px(l.width_px) + " " + px(l.height_px) +
         "\" font-family=\"DejaVu Sans, Helvetica, Arial, sans-serif\" font-size=\"12\">\n";
  out +=
      "<rect x=\"0\" y=\"0\" width=\"" + px(l.width_px) + "\" height=\"" + px(l.height_px) + "\" fill=\"#ffffff\"/>\n";
  if (!spec.title.empty()) {
    out += "<text class=\"title\" x=\"" + px(0.5 * l.width_px) +
           "\" y=\"20\" text-anchor=\"middle\" font-size=\"14\" font-weight=\"bold\">" + escapeXml(spec.title) +
           "</text>\n";
  }
}

void renderGrid(std::string& out, const PlotLayout& l) {
  out += "<g class=\"grid\" stroke=\"#e6e6e6\" stroke-width=\"1\">\n";
  for (const double v : l.x.values) {
    const std::string x = px(l.xToPx(v));
    out += "<line x1=\"" + x + "\" y1=\"" + px(l.top_px) + "\" x2=\"" + x + "\" y2=\"" + px(l.bottom_px) + "\"/>\n";
  }
  for (const double v : l.y.values) {
    const std::string y = px(l.yToPx(v));
    out += "<line x1=\"" + px(l.left_px) + "\" y1=\"" + y + "\" x2=\"" + px(l.right_px) + "\" y2=\"" + y + "\"/>\n";
  }
  out += "</g>\n";
}

void renderAxes(std::string& out, const PlotLayout& l) {
  const double w = l.right_px - l.left_px;
  const double h = l.bottom_px - l.top_px;
  out += "<g class=\"axes\" stroke=\"#333333\" stroke-width=\"1\">\n";
  out += "<rect x=\"" + px(l.left_px) + "\" y=\"" + px(l.top_px) + "\" width=\"" + px(w) + "\" height=\"" + px(h) +
         "\" fill=\"none\"/>\n";
  for (const double v : l.x.values) {
    const std::string x = px(l.xToPx(v));
    out += "<line x1=\"" + x + "\" y1=\"" + px(l.bottom_px) + "\" x2=\"" + x + "\" y2=\"" + px(l.bottom_px + 4.0) +
           "\"/>\n";
  }
  for (const double v : l.y.values) {
    const std::string y = px(l.yToPx(v));
    out +=
        "<line x1=\"" + px(l.left_px - 4.0) + "\" y1=\"" + y + "\" x2=\"" + px(l.left_px) + "\" y2=\"" + y + "\"/>\n";
  }
  out += "</g>\n";
}

void renderTickLabels(std::string& out, const PlotLayout& l) {
  out += "<g class=\"tick-labels\" fill=\"#333333\">\n";
  for (std::size_t i = 0; i < l.x.values.size(); ++i) {
    out += "<text class=\"tick-x\" x=\"" + px(l.xToPx(l.x.values[i])) + "\" y=\"" + px(l.bottom_px + 16.0) +
           "\" text-anchor=\"middle\">" + tickText(l.x, i) + "</text>\n";
  }
  for (std::size_t i = 0; i < l.y.values.size(); ++i) {
    out += "<text class=\"tick-y\" x=\"" + px(l.left_px - 7.0) + "\" y=\"" + px(l.yToPx(l.y.values[i])) +
           "\" dy=\"0.35em\" text-anchor=\"end\">" + tickText(l.y, i) + "</text>\n";
  }
  out += "</g>\n";
}

void renderAxisTitles(std::string& out, const PlotSpec& spec, const PlotLayout& l) {
  const std::string x_title = axisTitle(spec.x_label, spec.x_unit);
  const std::string y_title = axisTitle(spec.y_label, spec.y_unit);
  if (!x_title.empty()) {
    out += "<text class=\"axis-label\" x=\"" + px(0.5 * (l.left_px + l.right_px)) + "\" y=\"" + px(l.height_px - 12.0) +
           "\" text-anchor=\"middle\">" + escapeXml(x_title) + "</text>\n";
  }
  if (!y_title.empty()) {
    const std::string cy = px(0.5 * (l.top_px + l.bottom_px));
    out += "<text class=\"axis-label\" x=\"16\" y=\"" + cy + "\" text-anchor=\"middle\" transform=\"rotate(-90 16 " +
           cy + ")\">" + escapeXml(y_title) + "</text>\n";
  }
}

// The data, clipped to the plot area by a nested viewport whose user space is the outer one.
void openPlotArea(std::string& out, const PlotLayout& l) {
  const double w = l.right_px - l.left_px;
  const double h = l.bottom_px - l.top_px;
  out += "<svg class=\"plot-area\" x=\"" + px(l.left_px) + "\" y=\"" + px(l.top_px) + "\" width=\"" + px(w) +
         "\" height=\"" + px(h) + "\" viewBox=\"" + px(l.left_px) + " " + px(l.top_px) + " " + px(w) + " " + px(h) +
         "\" overflow=\"hidden\">\n";
}

void renderBands(std::string& out, const PlotSpec& spec, const PlotLayout& l) {
  for (const PlotBand& b : spec.bands) {
    if (!std::isfinite(b.low) || !std::isfinite(b.high)) continue;
    const double top = std::max(b.low, b.high);
    const double low = std::min(b.low, b.high);
    if (!onAxis(top, l.y.log)) continue;
    const double y_top = l.yToPx(top);
    const double y_bottom = onAxis(low, l.y.log) ? l.yToPx(low) : l.bottom_px;
    const double x_left = onAxis(b.x_low, l.x.log) ? l.xToPx(b.x_low) : l.left_px;
    const double x_right = onAxis(b.x_high, l.x.log) ? l.xToPx(b.x_high) : l.right_px;
    out += "<rect class=\"band\" x=\"" + px(x_left) + "\" y=\"" + px(y_top) + "\" width=\"" + px(x_right - x_left) +
           "\" height=\"" + px(y_bottom - y_top) + "\" fill=\"" + escapeXml(b.colour) + "\" fill-opacity=\"" +
           formatFixed(b.opacity, 3) + "\"/>\n";
  }
}

void renderReferenceLines(std::string& out, const PlotSpec& spec, const PlotLayout& l) {
  for (const PlotLine& line : spec.lines) {
    const bool horizontal = line.orientation == LineOrientation::kHorizontal;
    if (!onAxis(line.value, horizontal ? l.y.log : l.x.log)) continue;
    std::string coords;
    if (line.orientation == LineOrientation::kHorizontal) {
      const std::string y = px(l.yToPx(line.value));
      coords = "x1=\"" + px(l.left_px) + "\" y1=\"" + y + "\" x2=\"" + px(l.right_px) + "\" y2=\"" + y + "\"";
    } else {
      const std::string x = px(l.xToPx(line.value));
      coords = "x1=\"" + x + "\" y1=\"" + px(l.top_px) + "\" x2=\"" + x + "\" y2=\"" + px(l.bottom_px) + "\"";
    }
    out += "<line class=\"ref-line\" " + coords + " stroke=\"" + escapeXml(line.colour) + "\" stroke-width=\"1.5\"" +
           dashAttr(line.dashed, "5 4") + "/>\n";
  }
}

// A line series (or a joined marker series' line): a <polyline> per run of finite points, a dot for a lone one.
// Returns whether it has a point to show.
bool renderLine(std::string& out, const PlotSeries& s, std::size_t si, const PlotLayout& l) {
  bool any_point = false;
  const std::string colour = escapeXml(seriesColour(s, si));
  const std::string index = std::to_string(si);
  const std::string opacity = s.opacity < 1.0
                                  ? " stroke-opacity=\"" + formatFixed(std::max(s.opacity, 0.0), 3) +
                                        "\" fill-opacity=\"" + formatFixed(std::max(s.opacity, 0.0), 3) + "\""
                                  : std::string();
  std::vector<double> sx(s.x.size());
  std::vector<double> sy(s.y.size());
  for (std::size_t i = 0; i < s.x.size(); ++i) {
    const bool shown = l.plottable(s.x[i], s.y[i]);
    sx[i] = shown ? l.xToPx(s.x[i]) : kNan;
    sy[i] = shown ? l.yToPx(s.y[i]) : kNan;
  }
  std::size_t i = 0;
  while (i < sx.size()) {
    if (std::isnan(sx[i])) {
      ++i;
      continue;
    }
    std::size_t end = i;
    while (end < sx.size() && !std::isnan(sx[end])) ++end;
    any_point = true;
    if (end - i == 1 && s.marker != MarkerShape::kNone) {
      // A joined marker series' lone point: its marker (drawn below) is the point.
    } else if (end - i == 1) {
      out += "<circle class=\"point\" data-series=\"" + index + "\" cx=\"" + px(sx[i]) + "\" cy=\"" + px(sy[i]) +
             "\" r=\"2\" fill=\"" + colour + "\"" + opacity + "/>\n";
    } else {
      std::string points;
      for (const std::size_t k : thin(sx, sy, i, end)) {
        if (!points.empty()) points += ' ';
        points += px(sx[k]) + "," + px(sy[k]);
      }
      out += "<polyline class=\"series\" data-series=\"" + index + "\" fill=\"none\" stroke=\"" + colour +
             "\" stroke-width=\"" + formatFixed(s.width_px, 2) + "\" stroke-linejoin=\"round\"" + opacity +
             seriesDash(s, si) + " points=\"" + points + "\"/>\n";
    }
    i = end;
  }
  return any_point;
}

// Every series with its error bars. Returns whether any point was drawn.
bool renderSeries(std::string& out, const PlotSpec& spec, const PlotLayout& l) {
  bool any_point = false;
  for (std::size_t si = 0; si < spec.series.size(); ++si) {
    const PlotSeries& s = spec.series[si];
    renderErrorBars(out, s, si, l);
    if (s.marker != MarkerShape::kNone && !s.joined) {
      any_point = renderMarkers(out, s, si, l) || any_point;
      continue;
    }
    any_point = renderLine(out, s, si, l) || any_point;
    if (s.marker != MarkerShape::kNone) renderMarkers(out, s, si, l);
  }
  return any_point;
}

// What the plot area cannot show: the points a log axis dropped, or that there is nothing at all.
void renderNotes(std::string& out, const PlotLayout& l, bool any_point) {
  if (l.dropped_points > 0) {
    out += "<text class=\"dropped-note\" x=\"" + px(l.left_px + 6.0) + "\" y=\"" + px(l.bottom_px - 6.0) +
           "\" fill=\"#888888\" font-size=\"11\">" + std::to_string(l.dropped_points) +
           " point(s) &lt;= 0 not shown on the log axis</text>\n";
  }
  if (!any_point) {
    out += "<text class=\"no-data\" x=\"" + px(0.5 * (l.left_px + l.right_px)) + "\" y=\"" +
           px(0.5 * (l.top_px + l.bottom_px)) + "\" text-anchor=\"middle\" fill=\"#888888\">no data</text>\n";
  }
}

void renderLegend(std::string& out, const PlotSpec& spec, const PlotLayout& l) {
  const std::vector<LegendEntry> legend = legendEntries(spec);
  if (!legend.empty()) {
    out += "<g class=\"legend\">\n";
    const double x = l.right_px + kLegendGap;
    for (std::size_t i = 0; i < legend.size(); ++i) {
      const double y = l.top_px + 9.0 + kLegendRow * static_cast<double>(i);
      renderLegendSwatch(out, legend[i], x, y);
      out += "<text x=\"" + px(x + kLegendSwatch + 6.0) + "\" y=\"" + px(y) + "\" dy=\"0.35em\">" +
             escapeXml(legend[i].label) + "</text>\n";
    }
    out += "</g>\n";
  }
}

}  // namespace

MarkerShape markerShape(std::size_t index) {
  static constexpr std::array<MarkerShape, 5> kShapes{MarkerShape::kDot, MarkerShape::kSquare, MarkerShape::kTriangle,
                                                      MarkerShape::kDiamond, MarkerShape::kCross};
  return kShapes[index % kShapes.size()];
}

const std::string& dashPattern(std::size_t index) {
  static const std::array<std::string, 4> kPatterns{"", "6 4", "2 3", "8 3 2 3"};
  return kPatterns[index % kPatterns.size()];
}

std::string escapeXml(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&#39;";
        break;
      default:
        out += c;
        break;
    }
  }
  return out;
}

const std::string& paletteColour(std::size_t index) {
  // matplotlib's tab10: distinguishable, and the first two (blue, orange) read well side by side.
  static const std::array<std::string, 10> kPalette{"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd",
                                                    "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"};
  return kPalette[index % kPalette.size()];
}

std::string renderSvg(const PlotSpec& spec) {
  const PlotLayout l = layoutPlot(spec);
  std::string out;
  renderBackground(out, spec, l);
  // Grid, frame, ticks and their labels.
  renderGrid(out, l);
  renderAxes(out, l);
  renderTickLabels(out, l);
  renderAxisTitles(out, spec, l);
  openPlotArea(out, l);
  renderBands(out, spec, l);
  renderReferenceLines(out, spec, l);
  const bool any_point = renderSeries(out, spec, l);
  if (spec.equal_aspect && spec.track_markers) renderTrackMarkers(out, spec, l);
  renderNotes(out, l, any_point);
  out += "</svg>\n";  // the plot area ends here: the legend beside it is not clipped
  renderLegend(out, spec, l);
  out += "</svg>\n";
  return out;
}

}  // namespace swa::monitor

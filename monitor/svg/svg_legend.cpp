#include "svg_legend.h"

#include "svg_markers.h"

#include <algorithm>

namespace swa::monitor::svg {

std::string px(double v) { return formatFixed(std::clamp(v, -kCoordLimit, kCoordLimit), 2); }

std::string seriesColour(const PlotSeries& s, std::size_t index) {
  return s.colour.empty() ? paletteColour(index) : s.colour;
}

bool seriesDashed(const PlotSeries& s, std::size_t index) { return s.dashed || (s.colour.empty() && index >= 10); }

std::vector<LegendEntry> legendEntries(const PlotSpec& spec) {
  std::vector<LegendEntry> entries;
  for (std::size_t i = 0; i < spec.series.size(); ++i) {
    const PlotSeries& s = spec.series[i];
    if (!s.label.empty()) {
      entries.push_back({LegendKind::kSeries, s.label, seriesColour(s, i), seriesDashed(s, i), s.opacity, s.marker,
                         s.dash_pattern, s.joined});
    }
  }
  for (const PlotBand& b : spec.bands) {
    if (!b.label.empty()) entries.push_back({LegendKind::kBand, b.label, b.colour, false, b.opacity});
  }
  for (const PlotLine& l : spec.lines) {
    if (!l.label.empty()) entries.push_back({LegendKind::kLine, l.label, l.colour, l.dashed});
  }
  const bool tracks = std::any_of(spec.series.begin(), spec.series.end(),
                                  [](const PlotSeries& s) { return s.marker == MarkerShape::kNone; });
  if (spec.equal_aspect && spec.track_markers && tracks) {
    entries.push_back({LegendKind::kStart, "start", "#333333"});
    entries.push_back({LegendKind::kEnd, "end", "#333333"});
  }
  return entries;
}

std::string dashAttr(bool dashed, const char* pattern) {
  return dashed ? std::string(" stroke-dasharray=\"") + pattern + "\"" : std::string();
}

void renderLegendSwatch(std::string& out, const LegendEntry& e, double x, double y) {
  const std::string colour = escapeXml(e.colour);
  if (e.kind == LegendKind::kSeries && e.marker != MarkerShape::kNone && !e.joined) {
    renderMarker(out, e.marker, x + 0.5 * kLegendSwatch, y, 5.0, colour, "");
    return;
  }
  switch (e.kind) {
    case LegendKind::kSeries:
    case LegendKind::kLine:
      out += "<line x1=\"" + px(x) + "\" y1=\"" + px(y) + "\" x2=\"" + px(x + kLegendSwatch) + "\" y2=\"" + px(y) +
             "\" stroke=\"" + colour + "\" stroke-width=\"2\"" +
             (e.opacity < 1.0 ? " stroke-opacity=\"" + formatFixed(std::max(e.opacity, 0.0), 3) + "\"" : "") +
             (e.dash.empty() ? dashAttr(e.dashed, e.kind == LegendKind::kSeries ? "6 4" : "5 4")
                             : " stroke-dasharray=\"" + escapeXml(e.dash) + "\"") +
             "/>\n";
      if (e.marker != MarkerShape::kNone) renderMarker(out, e.marker, x + 0.5 * kLegendSwatch, y, 5.0, colour, "");
      break;
    case LegendKind::kBand:
      out += "<rect x=\"" + px(x) + "\" y=\"" + px(y - 5.0) + "\" width=\"" + px(kLegendSwatch) +
             "\" height=\"10\" fill=\"" + colour + "\" fill-opacity=\"" + formatFixed(e.opacity, 3) + "\"/>\n";
      break;
    case LegendKind::kStart:
      out += "<circle cx=\"" + px(x + 0.5 * kLegendSwatch) + "\" cy=\"" + px(y) +
             "\" r=\"4\" fill=\"#ffffff\" stroke=\"" + colour + "\" stroke-width=\"1.5\"/>\n";
      break;
    case LegendKind::kEnd:
      out += "<rect x=\"" + px(x + 0.5 * kLegendSwatch - 3.5) + "\" y=\"" + px(y - 3.5) +
             "\" width=\"7\" height=\"7\" fill=\"" + colour + "\"/>\n";
      break;
  }
}

}  // namespace swa::monitor::svg

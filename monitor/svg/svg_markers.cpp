#include "svg_markers.h"

#include <cmath>

#include "svg_legend.h"

namespace swa::monitor::svg {

void renderMarker(std::string& out, MarkerShape shape, double x, double y, double radius, const std::string& colour,
                  const std::string& attributes) {
  if (shape == MarkerShape::kCross) {
    const double r = 0.7 * radius;
    out += "<path" + attributes + " d=\"M" + px(x - r) + " " + px(y - r) + "L" + px(x + r) + " " + px(y + r) + "M" +
           px(x - r) + " " + px(y + r) + "L" + px(x + r) + " " + px(y - r) + "\" fill=\"none\" stroke=\"" + colour +
           "\" stroke-width=\"1.5\"/>\n";
    return;
  }
  // A white rim keeps a marker readable where it sits on a line or another marker.
  const std::string rim = "\" fill=\"" + colour + "\" stroke=\"#ffffff\" stroke-width=\"1.5\"/>\n";
  switch (shape) {
    case MarkerShape::kSquare: {
      // The same area as the dot's circle would look bigger: a square of side 1.6 r looks about as heavy.
      const double h = 0.8 * radius;
      out += "<rect" + attributes + " x=\"" + px(x - h) + "\" y=\"" + px(y - h) + "\" width=\"" + px(2.0 * h) +
             "\" height=\"" + px(2.0 * h) + rim;
      return;
    }
    case MarkerShape::kTriangle: {
      // Apex up, centred on the point's centroid (1/3 of the height above the base).
      const double r = 1.1 * radius;
      out += "<path" + attributes + " d=\"M" + px(x) + " " + px(y - r) + "L" + px(x + 0.866 * r) + " " +
             px(y + 0.5 * r) + "L" + px(x - 0.866 * r) + " " + px(y + 0.5 * r) + "Z" + rim;
      return;
    }
    case MarkerShape::kDiamond: {
      const double r = 1.1 * radius;
      out += "<path" + attributes + " d=\"M" + px(x) + " " + px(y - r) + "L" + px(x + r) + " " + px(y) + "L" + px(x) +
             " " + px(y + r) + "L" + px(x - r) + " " + px(y) + "Z" + rim;
      return;
    }
    default:
      out += "<circle" + attributes + " cx=\"" + px(x) + "\" cy=\"" + px(y) + "\" r=\"" + formatFixed(radius, 2) + rim;
      return;
  }
}

bool renderMarkers(std::string& out, const PlotSeries& s, std::size_t index, const PlotLayout& l) {
  const std::string colour = escapeXml(seriesColour(s, index));
  const std::string series = " data-series=\"" + std::to_string(index) + "\"";
  const std::string opacity =
      s.opacity < 1.0 ? " opacity=\"" + formatFixed(std::max(s.opacity, 0.0), 3) + "\"" : std::string();
  const double radius = std::max(s.marker_px, 0.5);
  bool any = false;
  for (std::size_t i = 0; i < s.x.size(); ++i) {
    if (!l.plottable(s.x[i], s.y[i])) continue;
    any = true;
    const double x = l.xToPx(s.x[i]);
    const double y = l.yToPx(s.y[i]);
    renderMarker(out, s.marker, x, y, radius, colour, " class=\"marker\"" + series + opacity);
    if (i < s.point_labels.size() && !s.point_labels[i].empty()) {
      out += "<text class=\"point-label\"" + series + " x=\"" + px(x + radius + 2.0) + "\" y=\"" +
             px(y - radius - 1.0) + "\" font-size=\"11\" font-weight=\"bold\" fill=\"#1d2430\">" +
             escapeXml(s.point_labels[i]) + "</text>\n";
    }
  }
  return any;
}

void renderTrackMarkers(std::string& out, const PlotSpec& spec, const PlotLayout& l) {
  for (std::size_t si = 0; si < spec.series.size(); ++si) {
    const PlotSeries& s = spec.series[si];
    if (s.marker != MarkerShape::kNone) continue;
    std::size_t first = s.x.size();
    std::size_t last = s.x.size();
    for (std::size_t i = 0; i < s.x.size(); ++i) {
      if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) continue;
      if (first == s.x.size()) first = i;
      last = i;
    }
    if (first == s.x.size()) continue;
    const std::string colour = escapeXml(seriesColour(s, si));
    const std::string index = std::to_string(si);
    out += "<circle class=\"start-marker\" data-series=\"" + index + "\" cx=\"" + px(l.xToPx(s.x[first])) + "\" cy=\"" +
           px(l.yToPx(s.y[first])) + "\" r=\"4\" fill=\"#ffffff\" stroke=\"" + colour + "\" stroke-width=\"1.5\"/>\n";
    out += "<rect class=\"end-marker\" data-series=\"" + index + "\" x=\"" + px(l.xToPx(s.x[last]) - 3.5) + "\" y=\"" +
           px(l.yToPx(s.y[last]) - 3.5) + "\" width=\"7\" height=\"7\" fill=\"" + colour + "\"/>\n";
  }
}

}  // namespace swa::monitor::svg

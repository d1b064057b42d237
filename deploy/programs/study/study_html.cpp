#include "study_html.h"

#include <string_view>
#include <vector>

#include "study_plots.h"
#include "swa/monitor/report_html.h"
#include "swa/monitor/svg_plot.h"

namespace swa::study {
namespace {

std::string esc(std::string_view text) { return monitor::escapeXml(text); }

// "a", "a and b", "a, b and c".
std::string listed(const std::vector<std::string>& items) {
  std::string out;
  for (std::size_t i = 0; i < items.size(); ++i) {
    if (i > 0) out += i + 1 == items.size() ? " and " : ", ";
    out += items[i];
  }
  return out;
}

// The scenario file's name without its directory and extension: what a reader calls it.
std::string scenarioName(const std::string& path) {
  std::string name = path.substr(path.find_last_of('/') + 1);  // npos + 1 == 0: no directory
  for (const std::string_view ext : {".yaml", ".yml"}) {
    if (name.size() > ext.size() && name.compare(name.size() - ext.size(), ext.size(), ext) == 0) {
      name.resize(name.size() - ext.size());
      break;
    }
  }
  return name.empty() ? path : name;
}

// A swept key as the title names it; the variants by their names.
std::string axisName(const Axis& a) {
  if (a.key != kVariantAxis) return a.key;
  return "variants " + listed(a.values);
}

std::string infoTable(const StudyRecord& s) {
  std::string html = "<table class=\"info\">\n";
  const auto row = [&html](const std::string& key, const std::string& value) {
    html += "<tr><th>" + esc(key) + "</th><td>" + esc(value) + "</td></tr>\n";
  };
  row("scenario", s.scenario);
  row("study id", s.study_id);
  row("version", s.version);
  for (const Axis& a : s.plan.axes) {
    std::string text;
    for (const std::string& v : a.values) text += (text.empty() ? "" : ", ") + v;
    row("swept " + a.key, text);
  }
  for (const Variant& v : s.plan.variants) {
    std::string text;
    for (const std::string& o : v.overrides) text += (text.empty() ? "" : ", ") + o;
    row("variant " + v.name, text);
  }
  row("seeds", std::to_string(s.first_seed) + " .. " +
                   std::to_string(s.first_seed + static_cast<std::uint64_t>(s.plan.seeds) - 1) + " (" +
                   std::to_string(s.plan.seeds) + " per grid point, " + std::to_string(s.runs.size()) + " runs)");
  return html + "</table>\n";
}

std::string figure(const StudyPlot& plot) {
  std::string html = "<figure>\n" + monitor::renderSvg(plot.spec);
  if (!plot.notes.empty()) {
    std::string notes;
    for (const std::string& n : plot.notes) notes += (notes.empty() ? "" : " ") + n;
    html += "<figcaption class=\"note\">" + esc(notes) + "</figcaption>\n";
  }
  return html + "</figure>\n";
}

// Metric `m`'s numbers: one row per grid point, its values, then mean, standard deviation and seeds with a value.
std::string numbersTable(const StudyView& view, const StudyMetric& m) {
  const StudyPlan& plan = view.study.plan;
  std::string html = "<h3>" + esc(m.label) + (*m.unit ? " [" + esc(m.unit) + "]" : std::string()) +
                     "</h3>\n<table class=\"numbers\" data-metric=\"" + esc(m.key) + "\">\n<thead><tr>";
  for (const Axis& a : plan.axes) html += "<th>" + esc(a.key) + "</th>";
  html += "<th>mean</th><th>sd</th><th>n</th></tr></thead>\n<tbody>\n";
  for (std::size_t point = 0; point < pointCount(plan); ++point) {
    const Stats st = statsOf(view.values(point, m.key));
    html += "<tr>";
    for (const std::string& v : pointValues(plan, point)) html += "<td>" + esc(v) + "</td>";
    html += "<td class=\"num\">" + esc(monitor::formatReportValue(st.mean)) + "</td><td class=\"num\">" +
            esc(monitor::formatReportValue(st.n > 1 ? st.std : monitor::kNaN)) + "</td><td class=\"num\">" +
            std::to_string(st.n) + "</td></tr>\n";
  }
  return html + "</tbody>\n</table>\n";
}

constexpr const char* kStyle =
    "body{font-family:sans-serif;margin:2em;color:#1d2430;max-width:60em}h2{margin-top:2em}"
    ".note{color:#555;font-size:90%}figure{margin:1.5em 0}figcaption{max-width:760px}\n"
    "table{border-collapse:collapse}td,th{border:1px solid #ccc;padding:2px 8px;text-align:left}"
    "td.num{text-align:right;font-variant-numeric:tabular-nums}\n";

}  // namespace

std::string studyTitle(const StudyRecord& s) {
  std::vector<std::string> keys;
  for (const Axis& a : s.plan.axes) keys.push_back(axisName(a));
  return "Formation, drift, safety and consistency against " + listed(keys) + " — scenario " + scenarioName(s.scenario);
}

std::string studyHtml(const StudyRecord& s) {
  const StudyView view(s);
  const std::string title = esc(studyTitle(s));
  std::string html = "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>" + title +
                     "</title>\n<style>" + kStyle + "</style></head><body>\n<h1>" + title + "</h1>\n";
  html += infoTable(s);
  html +=
      "<p class=\"note\">Markers: the mean over the seeds at each grid point; bars: ± one standard deviation of the "
      "single runs (the spread of a run, not the uncertainty of the mean). Where several series share a value, their "
      "markers are drawn a little apart so that equal values stay visible; each belongs at the value under the "
      "group. The numbers are at the end; runs.csv has every run, points/&lt;k&gt;/summary.json every grid point's "
      "aggregate.</p>\n";
  for (std::size_t axis = 0; axis < s.plan.axes.size(); ++axis) {
    html += "<h2>Against " + esc(axisName(s.plan.axes[axis])) + "</h2>\n";
    for (const StudyMetric& m : studyMetrics()) html += figure(studyPlot(view, axis, m));
  }
  html +=
      "<h2 id=\"numbers\">The numbers</h2>\n<p class=\"note\">Per grid point: the mean over its seeds, the sample "
      "standard deviation (— with fewer than two) and n, the seeds with a value.</p>\n";
  for (const StudyMetric& m : studyMetrics()) html += numbersTable(view, m);
  html += "</body></html>\n";
  return html;
}

}  // namespace swa::study

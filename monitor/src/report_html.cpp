#include "swa/monitor/report_html.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <stdexcept>
#include <system_error>

#include "report_text.h"

namespace swa::monitor {
namespace {

void appendText(std::string& out, const std::string& text) { out += escapeXml(text); }

std::string orDash(const std::string& text) { return text.empty() ? std::string("—") : text; }

const char* kStyle =
    "body{font-family:\"DejaVu Sans\",Helvetica,Arial,sans-serif;color:#222;max-width:1180px;margin:24px auto;"
    "padding:0 16px;line-height:1.4}\n"
    "h1{font-size:1.6em;margin-bottom:0.2em}\n"
    "h2{font-size:1.25em;margin-top:1.6em;border-bottom:1px solid #ddd;padding-bottom:4px}\n"
    "dl.notes{display:grid;grid-template-columns:max-content auto;gap:2px 16px}\n"
    "dl.notes dt{font-weight:bold}\n"
    "dl.notes dd{margin:0}\n"
    "table.summary{border-collapse:collapse;font-size:14px}\n"
    "table.summary th,table.summary td{border:1px solid #ddd;padding:3px 10px;text-align:right}\n"
    "table.summary thead th{background:#f2f2f2;text-align:center}\n"
    "table.summary th[scope=row]{text-align:left;font-family:monospace;font-weight:normal}\n"
    "table.summary tbody tr:nth-child(even){background:#fafafa}\n"
    "table.summary td.verdict{text-align:left;max-width:320px}\n"
    "table.data{border-collapse:collapse;font-size:14px}\n"
    "table.data th,table.data td{border:1px solid #ddd;padding:3px 10px;text-align:left}\n"
    "table.data thead th{background:#f2f2f2}\n"
    "table.data tbody tr:nth-child(even){background:#fafafa}\n"
    "dl.verdicts{display:grid;grid-template-columns:max-content auto;gap:2px 16px;font-size:1.1em}\n"
    "dl.verdicts dt{font-weight:bold}\n"
    "dl.verdicts dd{margin:0}\n"
    "figure{margin:16px 0}\n"
    "figure>svg{max-width:100%;height:auto;border:1px solid #eee}\n"
    "figcaption{font-size:13px;color:#555;max-width:720px}\n"
    ".trajectories{display:flex;flex-wrap:wrap;gap:0 24px}\n"
    "footer{margin-top:2em;font-size:12px;color:#777}\n";

void appendTable(std::string& out, const ReportTable& table, std::size_t index) {
  out += "<section id=\"table-";
  appendText(out, reportFileStem(table.id, index));
  out += "\">\n<h2>";
  appendText(out, table.title);
  out += "</h2>\n";
  if (!table.note.empty()) {
    out += "<p>";
    appendText(out, table.note);
    out += "</p>\n";
  }
  if (table.rows.empty()) {
    out += "<p>";
    appendText(out, table.empty_text);
    out += "</p>\n</section>\n";
    return;
  }
  out += "<table class=\"data\">\n<thead><tr>";
  for (const std::string& c : table.columns) {
    out += "<th scope=\"col\">";
    appendText(out, c);
    out += "</th>";
  }
  out += "</tr></thead>\n<tbody>\n";
  for (const std::vector<std::string>& row : table.rows) {
    out += "<tr>";
    for (std::size_t c = 0; c < std::max(row.size(), table.columns.size()); ++c) {
      out += "<td>";
      if (c < row.size()) appendText(out, row[c]);
      out += "</td>";
    }
    out += "</tr>\n";
  }
  out += "</tbody>\n</table>\n</section>\n";
}

// Opens a section about the runs; without runs it says so and closes it (false: nothing more to write).
bool openRunSection(std::string& out, const char* id, const char* title, const std::vector<RunReport>& runs) {
  out += std::string("<section id=\"") + id + "\">\n<h2>" + title + "</h2>\n";
  if (!runs.empty()) return true;
  out += "<p>No runs.</p>\n</section>\n";
  return false;
}

// Each run's verdict (PASS/FAIL/INCOMPLETE and its reasons), under the title.
void appendVerdicts(std::string& out, const std::vector<RunReport>& runs) {
  if (!openRunSection(out, "verdict", "Verdict", runs)) return;
  out += "<dl class=\"verdicts\">\n";
  for (const RunReport& run : runs) {
    out += "<dt>";
    appendText(out, run.label);
    out += "</dt><dd class=\"verdict\">";
    appendText(out, orDash(run.verdict));
    out += "</dd>\n";
  }
  out += "</dl>\n</section>\n";
}

// The time plots compare the runs; the trajectory plots sit side by side.
void appendPlots(std::string& out, const std::vector<RunReport>& runs, const ReportNotes& notes) {
  const std::vector<ReportPlot> plots = reportPlots(runs, notes);
  const auto figure = [&out](const ReportPlot& p) {
    out += "<figure id=\"plot-";
    appendText(out, p.name);
    out += "\">\n";
    out += renderSvg(p.spec);
    out += "<figcaption>";
    appendText(out, p.caption);
    out += "</figcaption>\n</figure>\n";
  };
  const std::size_t time_plots = plots.size() - runs.size();
  out += "<section id=\"plots\">\n<h2>Time series</h2>\n";
  for (std::size_t i = 0; i < time_plots; ++i) figure(plots[i]);
  out += "</section>\n";
  out += "<section id=\"trajectories\">\n<h2>Trajectories</h2>\n<div class=\"trajectories\">\n";
  for (std::size_t i = time_plots; i < plots.size(); ++i) figure(plots[i]);
  out += "</div>\n</section>\n";
}

void appendNotes(std::string& out, const std::vector<RunReport>& runs, const ReportNotes& notes) {
  out += "<section id=\"notes\">\n<h2>Notes</h2>\n<dl class=\"notes\">\n";
  std::string seeds;
  for (const std::uint64_t s : notes.seeds) seeds += (seeds.empty() ? "" : ", ") + std::to_string(s);
  std::string labels;
  for (const RunReport& run : runs) labels += (labels.empty() ? "" : ", ") + run.label;
  const std::vector<std::pair<std::string, std::string>> fixed{
      {"Scenario", orDash(notes.scenario)},
      {"Seeds", orDash(seeds)},
      {"Version", orDash(notes.version)},
      {"Runs", orDash(labels)},
      {"Formation radius r", metresText(notes.scoring.formation.radius_m)},
      {"Collision distance", metresText(notes.scoring.collision_distance_m)},
      {"GNSS lost at", std::isfinite(notes.gnss_loss_s) ? formatFixed(notes.gnss_loss_s, 3) + " s" : "—"}};
  for (const auto* list : {&fixed, &notes.extra}) {
    for (const auto& [key, value] : *list) {
      out += "<dt>";
      appendText(out, key);
      out += "</dt><dd>";
      appendText(out, value);
      out += "</dd>\n";
    }
  }
  out += "</dl>\n</section>\n";
}

// One column per run, one row per summaryFields key (the verdict again on top, beside the numbers it judged).
void appendSummary(std::string& out, const std::vector<RunReport>& runs) {
  if (!openRunSection(out, "summary", "Summary", runs)) return;
  out += "<table class=\"summary\">\n<thead><tr><th scope=\"col\">metric</th>";
  for (const RunReport& run : runs) {
    out += "<th scope=\"col\">";
    appendText(out, run.label);
    out += "</th>";
  }
  out += "</tr></thead>\n<tbody>\n<tr><th scope=\"row\">verdict</th>";
  for (const RunReport& run : runs) {
    out += "<td class=\"verdict\">";
    appendText(out, orDash(run.verdict));
    out += "</td>";
  }
  out += "</tr>\n";
  std::vector<std::vector<NamedValue>> fields;
  for (const RunReport& run : runs) fields.push_back(summaryFields(run.summary));
  for (std::size_t k = 0; k < fields.front().size(); ++k) {
    out += "<tr><th scope=\"row\">";
    appendText(out, fields.front()[k].key);
    out += "</th>";
    for (const std::vector<NamedValue>& f : fields) out += "<td>" + escapeXml(formatReportValue(f[k].value)) + "</td>";
    out += "</tr>\n";
  }
  out += "</tbody>\n</table>\n</section>\n";
}

}  // namespace

std::string formatReportValue(double value) {
  if (!std::isfinite(value)) return "—";
  if (value == std::floor(value) && std::fabs(value) < 1e15) return formatFixed(value, 0);
  std::array<char, 64> buf{};
  const auto r = std::to_chars(buf.data(), buf.data() + buf.size(), value, std::chars_format::general, 5);
  return r.ec == std::errc() ? std::string(buf.data(), r.ptr) : std::string("—");
}

std::string renderReportHtml(const std::vector<RunReport>& runs, const ReportNotes& notes) {
  std::string out;
  out += "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n";
  out += "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n<title>";
  appendText(out, notes.title);
  out += "</title>\n<style>\n";
  out += kStyle;
  out += "</style>\n</head>\n<body>\n<h1>";
  appendText(out, notes.title);
  out += "</h1>\n";
  // What a reader comes for first: the verdict and the pictures; then the facts and the long tables (issue #30).
  appendVerdicts(out, runs);
  appendPlots(out, runs, notes);
  appendNotes(out, runs, notes);
  appendSummary(out, runs);
  for (std::size_t t = 0; t < notes.tables.size(); ++t) appendTable(out, notes.tables[t], t);

  out += "<footer>Written by the SWA monitor";
  if (!notes.version.empty()) {
    out += ", version ";
    appendText(out, notes.version);
  }
  out += ". Summary keys as in summary.json.</footer>\n</body>\n</html>\n";
  return out;
}

std::vector<std::string> writeReport(const std::string& directory, const std::vector<RunReport>& runs,
                                     const ReportNotes& notes) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::create_directories(directory, ec);
  if (ec) throw std::runtime_error("writeReport: cannot create " + directory + ": " + ec.message());
  std::vector<std::string> written;
  const auto write = [&written](const fs::path& path, const std::string& content) {
    std::ofstream file(path, std::ios::binary | std::ios::trunc);
    file << content;
    file.close();
    if (!file) throw std::runtime_error("writeReport: cannot write " + path.string());
    written.push_back(path.string());
  };
  write(fs::path(directory) / "report.html", renderReportHtml(runs, notes));
  for (const ReportPlot& p : reportPlots(runs, notes)) {
    write(fs::path(directory) / (p.name + ".svg"), "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n" + renderSvg(p.spec));
  }
  return written;
}

}  // namespace swa::monitor

#pragma once
// report.html for one live run or for several runs side by side (--combine): the monitor library's report
// (monitor::writeReport) plus what only the live monitor knows: why each run ended, its verdict, its scenario
// events (agent dead / rejoined, collisions, failsafe, GNSS) and the launcher's agent restarts.

#include <string>
#include <vector>

#include "swa/monitor/report_html.h"
#include "swa/run_record/run_record.h"

namespace swa::record {

// Longest events / restarts table; the rest is summarised in the table's note (summary.json has them all).
constexpr std::size_t kMaxTableRows = 500;

std::vector<monitor::RunReport> reportRuns(const std::vector<RunRecord>& runs);

// Notes from the first run (scenario, r, tolerance, collision distance, GNSS loss line), the seeds of all runs,
// per-run extras (end, verdict, restarts, dropped inputs), and the events and restarts tables (with a run column
// when there is more than one run).
monitor::ReportNotes reportNotes(const std::vector<RunRecord>& runs, const std::string& title);

monitor::ReportTable eventsTable(const std::vector<RunRecord>& runs);
monitor::ReportTable restartsTable(const std::vector<RunRecord>& runs);

}  // namespace swa::record

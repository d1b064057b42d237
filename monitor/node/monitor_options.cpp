#include "monitor_options.h"

#include <set>

#include "swa/app/cli.h"
#include "swa/dds/deployment.h"
#include "swa/dds/options.h"

namespace swa::monitor_node {
namespace {

// Longest --timeout-s: far beyond any scenario, small enough for any clock arithmetic.
constexpr double kMaxTimeoutS = 1e6;

// The options that only make sense while joining a running swarm.
constexpr const char* kLiveOnly[] = {"--label",  "--domain",     "--restarts", "--timeout-s",
                                     "--record", "--record-set", "--live"};

const char* const kDetails = R"(Live mode (the default) joins a running swarm as the Fast DDS participant "swa_monitor":
Reads      swa/truth, swa/events, swa/uav<i>/state for every UAV (i < scenario uav_count with --scenario;
           without it, the UAV ids of the first truth sample)
It joins each truth sample with the agents' states of the same stamp (both on 100 ms boundaries): a step is
scored once every UAV whose agent is alive has reported, or once 5 later truth samples have arrived, or at the
end (a missing state means no estimate for that UAV at that step). Malformed input (out-of-order or duplicate
truth stamps, non-finite values, states of unknown UAVs or of stamps never seen in the truth) is dropped and
counted in summary.json, never fatal.
A UAV whose agent is dead still flies (failsafe hover): it stays in every metric; only its estimate is missing.

Scoring parameters:
  with --scenario     r = agent.formation.radius_m, metrics window from the common GNSS loss
                      (gnss.dropout_start_s), no NEES for agent.mode standalone; exactly what swa_batch uses
  without             r = 10 m, circle fit fixed_radius, window from the first EVENT_GNSS_LOST (the one for all
                      UAVs if any), else from 0; mode from the agents' states

The run ends on EVENT_SCENARIO_END, SIGINT / SIGTERM, or --timeout-s wall seconds without the end event. Then
it writes into --out DIR:
  summary.json       the summary keys of swa_batch's per-seed entries, plus label, mode, scenario, seed,
                     completed, end_reason, verdict, verdict_reasons, agent_restarts, restarts, dropped-input
                     counts, events
  timeseries.csv     one row per scored step (swa_batch's columns)
  trajectories.csv   t_s,uav,x_m,y_m every 0.5 s of sim time (nan: a gap)
  events.csv         t_s,kind,uav,other_uav,value,text
  report.html        plots, summary, events and agent restarts (and the plots as .svg files)
and prints the verdict and the report's path.

--record FILE.mcap  also records the run into one MCAP file (ROS 2's bag format; Foxglove, Lichtblick, PlotJuggler
  open it): every payload of swa/truth, swa/events, swa/clock and, per UAV, detections, imu, gnss, cmd_vel,
  state and bridge_state, unchanged (CDR, schemas: the swa_msgs .msg definitions, topics as ROS names
  /swa/uav0/imu), and the monitor's metrics per scored step on /swa/monitor/metrics (JSON). A message's log time
  is its header stamp (simulated time in a simulated run). Chunked and indexed for seeking; a chunk is written at
  least every second, so a crash loses at most the last second. Writes recording.json into --out: the file, and
  every channel's schema and message count.
  Receiving every UAV's sensors and commands is what a complete recording costs: about what a bare Fast DDS reader
  of those topics costs, several times the monitor alone (BENCHMARKS.md, issue #24). For a small, cheap file:
--record-set monitor  records only what the monitor reads anyway: swa/truth, swa/events, swa/uav<i>/state and
  /swa/monitor/metrics (no sensors, commands, bridge states or clock). The file says so in its metadata
  (swa_recording: record_set); swa_replay refuses it, as it needs the sensors and commands. Default: all.

--live [ADDR:]PORT  serves a live view on one port while the run goes on (off by default): GET / is a page with the
  swarm top-down and rolling d_NB, drift and minimum-separation plots (self-contained: no internet needed), and
  the same port speaks the Foxglove WebSocket protocol (subprotocol foxglove.websocket.v1 or foxglove.sdk.v1) for
  Foxglove and Lichtblick (open connection ws://ADDR:PORT): channels /swa/live/swarm (positions, neighbour links,
  floating-frame centres), /swa/live/uav<i>/state and /swa/monitor/metrics, JSON. ADDR defaults to 127.0.0.1: only
  this host can connect unless you give another address (0.0.0.0: every interface). PORT 0 picks a free port. The
  URL is printed on stderr.

Verdict (--tolerance F):
  PASS        EVENT_SCENARIO_END "completed", final d_NB (mean over the last 5 s) within r (1 +- F), no collision,
              one group at the end, and no UAV on failsafe at the end (every agent declared dead has rejoined)
  FAIL        completed, but one of those failed (reasons in summary.json and printed)
  INCOMPLETE  no "completed" end event: interrupted, timeout, the simulator reported a failure, or no truth
              at all; every output that can be written still is

--combine LABEL=DIR...  builds one report.html in --out from run directories written by live monitors (reads
  their summary.json, timeseries.csv, trajectories.csv, events.csv), one column per run (e.g. swa=out/swa
  standalone=out/standalone), and writes summary.json {"runs": [each run's summary with "label" = LABEL]}.
  r, the GNSS loss time and the scenario name come from --scenario if given, else from the first run.)";

app::Cli makeCli(MonitorOptions& o) {
  app::Cli cli("swa_monitor",
               "swarm metrics, verdict and report of a run, from ground truth and the agents' diagnostics.");
  cli.usage(R"(swa_monitor [--out DIR] [--scenario FILE [--set key=value]...] [--label NAME] [--domain D]
                   [--restarts FILE] [--timeout-s S] [--tolerance F] [--record FILE.mcap [--record-set all|monitor]]
                   [--live [ADDR:]PORT] [--quiet]
       swa_monitor --combine LABEL=DIR [LABEL=DIR]... --out DIR [--scenario FILE [--set key=value]...])");
  cli.details(kDetails);
  cli.path("--out", "DIR", o.out_dir, "output directory (required with --combine); created if needed");
  cli.scenario(o.scenario_path, "the run's scenario YAML (see swa_sim --parameters)");
  cli.overrides(o.overrides, "override a scenario key as given to swa_sim; needs --scenario");
  cli.text("--label", "NAME", o.label, "run name in the report and summary.json (default: the agents' mode, e.g. swa)",
           "a name");
  cli.domain(o.domain, dds::kMaxDomainId);
  cli.path("--restarts", "FILE", o.restarts_path,
           "the launcher's restart log, read at the end: CSV with header wall_s,uav,exit_status,restart_count,"
           "backoff_s and one row per agent restart (missing or empty file: no restart; malformed rows are counted "
           "and reported)");
  cli.real("--timeout-s", "S", o.timeout_s, 0.0, kMaxTimeoutS, "a wall time in seconds",
           "give up S wall seconds after start without EVENT_SCENARIO_END, 0 for never");
  cli.real("--tolerance", "F", o.tolerance, 0.0, 1.0, "a fraction of r",
           "PASS band for the final d_NB, as a fraction of r, not 0; with --combine only the band drawn in the "
           "report, by default the first run's");
  cli.path("--record", "FILE.mcap", o.record_path, "also record the run into this MCAP file (see below)");
  const std::vector<std::string> sets = recording::recordSetNames();
  cli.choice(
      "--record-set", "SET", sets, [&o, sets](std::size_t k) { o.record_set = *recording::recordSetFromName(sets[k]); },
      "what --record holds: all, every topic of the run (default; what swa_replay needs), or monitor, only "
      "truth, events, the agents' states and the metrics (see below); needs --record");
  cli.value(
      "--live", "[ADDR:]PORT",
      [&o](const std::string& v, app::Problems& p) {
        const std::size_t colon = v.rfind(':');
        const std::string address = colon == std::string::npos ? "127.0.0.1" : v.substr(0, colon);
        const std::string port = colon == std::string::npos ? v : v.substr(colon + 1);
        try {
          std::size_t used = 0;
          const int n = std::stoi(port, &used);
          if (used != port.size() || n < 0 || n > 65535 || address.empty()) throw std::invalid_argument(v);
          o.live_address = address;
          o.live_port = n;
        } catch (const std::exception&) {
          p.push_back("--live '" + v + "' is not [ADDR:]PORT with PORT in [0, 65535]");
        }
      },
      "serve the live view (page and Foxglove WebSocket) on this port, 127.0.0.1 unless ADDR (see below)");
  cli.flag("--quiet", o.quiet,
           "no status line (default: refreshed in place on a terminal, else a line every 10 s of sim time, on "
           "stderr)");
  cli.value(
      "--combine", "LABEL=DIR",
      [&o](const std::string& entry, app::Problems& p) {
        const auto eq = entry.find('=');
        if (eq == std::string::npos || eq == 0 || eq + 1 == entry.size()) {
          p.push_back("--combine '" + entry + "' is not LABEL=DIR");
        } else {
          o.combine.push_back({entry.substr(0, eq), entry.substr(eq + 1)});
        }
      },
      "offline mode: one report of these run directories, one column per LABEL (see below); the list goes "
      "on up to the next option, and --combine may be repeated",
      true);
  cli.footer(
      R"(Exit status: 0 PASS; 1 FAIL; 3 INCOMPLETE; 2 bad arguments or scenario, output directory not writable, DDS
             participant not created (nothing started). --combine: the verdict of the FIRST run (0, 1 or 3),
             2 for bad arguments or an unreadable run directory. 70: Fast DDS stuck inside its participant
             (deleting it took over 12 s).

)" + dds::environmentHelp());
  return cli;
}

// Completes what the options alone do not say: which were given, and how they go together.
void finish(MonitorOptions& o, const app::Cli& cli, app::Problems& problems) {
  o.out_given = cli.given("--out");
  o.tolerance_given = cli.given("--tolerance");
  if (o.tolerance_given && !(o.tolerance > 0.0)) problems.push_back("--tolerance must be > 0");
  if (!o.overrides.empty() && o.scenario_path.empty()) problems.push_back("--set needs --scenario");
  if (cli.given("--record-set") && o.record_path.empty() && !o.combineMode()) {
    problems.push_back("--record-set needs --record FILE.mcap (it says what the recording holds)");
  }
  if (!o.combineMode()) return;
  for (const char* live : kLiveOnly) {
    if (cli.given(live)) problems.push_back(std::string(live) + " applies to the live mode only, not to --combine");
  }
  if (!o.out_given) problems.push_back("--combine needs --out DIR (where the combined report goes)");
  std::set<std::string> labels;
  for (const CombineInput& c : o.combine) {
    if (!labels.insert(c.label).second) problems.push_back("--combine label '" + c.label + "' given twice");
  }
}

}  // namespace

MonitorOptions parseMonitorOptions(const std::vector<std::string>& args) {
  return app::parseOptions<MonitorOptions>(args, makeCli, finish);
}

std::string monitorUsage() { return app::helpText(makeCli); }

}  // namespace swa::monitor_node

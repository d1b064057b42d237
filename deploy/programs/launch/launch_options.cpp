#include "launch_options.h"

#include "swa/app/cli.h"
#include "swa/app/number.h"
#include "swa/dds/deployment.h"
#include "swa/dds/naming.h"
#include "swa/dds/options.h"

namespace swa::launch {
namespace {

const char* const kDetails = R"(What it does, per run:
  1. loads the scenario (with every --set) and stops here, exit 2, if anything is wrong with it;
  2. writes the effective scenario to DIR/scenario.yaml, which the simulator and the monitor read, and the agents'
     configuration it implies to DIR/agent.yaml (no --set is passed on), and starts swa_monitor, the agents
     (swa_agent --id I --config DIR/agent.yaml), with vehicle.interface = px4 or ardupilot a bridge per agent
     (swa_px4_bridge --id I --engage), and swa_sim (which waits until all of them are discovered);
  3. supervises: an agent (or bridge) that dies while the scenario runs is restarted after a back-off (0.5 s,
     doubling per restart of that process, at most 8 s; at most --max-restarts times), and every restart is
     appended to DIR/logs/restarts.csv, which the monitor puts into the report;
  4. when the simulator finishes, waits for the monitor's verdict, stops the agents, removes the shared-memory
     files of killed processes, and exits with the verdict.
Each child's output goes to DIR/logs/<name>.log (agent_<I>.log, sim.log, monitor.log). SIGINT / SIGTERM are
forwarded: the simulator ends the run early, the monitor writes what it has, everything is stopped and reaped,
within 15 s (8 s to end the run, then at most 5 s, or --grace-s if shorter, before a child is killed).

With --compare MODE, the same scenario and seed run a second time with agent.mode = MODE (e.g. standalone, the
paper's baseline) into DIR/<mode>/, the first run into DIR/<scenario mode>/, and DIR/report.html shows both side by
side. Without it the run's files are in DIR itself.)";

app::Cli makeCli(LaunchOptions& o) {
  app::Cli cli("swa_launch",
               "runs a scenario as processes: swa_sim, one swa_agent per UAV, and swa_monitor, on one DDS domain.");
  cli.usage("swa_launch --scenario FILE [--set key=value]... [--out DIR] [--compare standalone] [options]");
  cli.details(kDetails);
  cli.scenario(o.scenario_path, "scenario YAML (see deploy/scenarios/, swa_sim --parameters)");
  cli.required("--scenario");
  cli.overrides(o.overrides, "override a scenario key, e.g. --set duration_s=60 --set uav_count=12");
  cli.path("--out", "DIR", o.out_dir,
           "output directory; the files an earlier launch wrote there are removed first, nothing else");
  cli.choice("--compare", "MODE", {agent::Mode::kStandalone, agent::Mode::kSwa, agent::Mode::kAnchored}, o.compare,
             "also run the baseline in that mode, with the same seed");
  cli.domain(o.domain, dds::kMaxDomainId, "use distinct domains for launches that run at the same time");
  cli.path("--bin-dir", "DIR", o.bin_dir, "where swa_sim, swa_agent, swa_monitor are (default: next to swa_launch)");
  cli.integer("--max-restarts", "N", o.max_restarts, 0, 1000, "a count", "restarts per agent and run");
  cli.real("--restart-backoff-s", "T", o.restart_backoff_s, 0.0, 600.0, "a delay in seconds", "first restart delay");
  cli.real("--restart-backoff-max-s", "T", o.restart_backoff_max_s, 0.0, 3600.0, "a delay in seconds", "back-off cap");
  cli.real("--agent-timeout-s", "T", o.agent_timeout_s, 1e-3, 3600.0, "a timeout in seconds",
           "lockstep: an agent silent this long is declared dead by the simulator");
  cli.real("--timeout-s", "T", o.timeout_s, 0.0, 1e6, "a timeout in seconds",
           "wall-clock bound per run, 0 for none; the run is then stopped like on SIGINT");
  cli.real("--grace-s", "T", o.grace_s, 0.0, 600.0, "a grace period in seconds",
           "how long a stopped child may take before it is killed (at most 5 s after SIGINT / SIGTERM)");
  cli.value(
      "--stagger-s", "T",
      [&o](const std::string& v, app::Problems& problems) {
        o.stagger_s = app::parseReal(v, 0.0, 10.0);
        if (!o.stagger_s) problems.push_back("--stagger-s '" + v + "' is not a delay in seconds in [0, 10]");
      },
      "start the simulator and the monitor first, then one UAV process (agent, bridge) every T s; 0 starts all at "
      "once, the simulator last (default: " +
          app::formatNumber(kSecureStaggerS) +
          " with --secure, whose authentication handshakes stall when many processes start together; else 0)");
  std::vector<std::string> transports;
  for (const auto t : {dds::Transport::kLocal, dds::Transport::kNetwork, dds::Transport::kDiscoveryServer}) {
    transports.emplace_back(dds::transportName(t));
  }
  cli.choice(
      "--transport", "T", transports, [&o, transports](std::size_t k) { o.transport = transports[k]; },
      "local: shared memory + UDP, one host; network: UDPv4 only, multicast discovery; discovery-server: "
      "UDPv4, discovery through a Fast DDS Discovery Server. Sets SWA_TRANSPORT for every child (default: "
      "$SWA_TRANSPORT, else local, or discovery-server past " +
          std::to_string(kMaxUavProcessesForSimpleDiscovery) + " UAV processes; deploy/README.md: when to use which)");
  cli.text("--discovery-server", "LIST", o.discovery_server,
           "with discovery-server: the servers' IP:PORT[;IP:PORT...]; without it swa_launch starts one "
           "(fast-discovery-server -i 0) on 127.0.0.1:--discovery-port and stops it at the end");
  cli.value(
      "--discovery-port", "P",
      [&o](const std::string& v, app::Problems& p) {
        if (const auto port = app::parseInteger(v, 1024, 65535)) {
          o.discovery_port = static_cast<int>(*port);
        } else {
          p.push_back("--discovery-port '" + v + "' is not a port in [1024, 65535]");
        }
      },
      "port of the server swa_launch starts (default: the first free one from 11811)");
  cli.text("--secure", "DIR", o.secure_dir,
           "DDS Security: authenticated, encrypted, per-UAV permissions, with the credentials in DIR (create them "
           "with deploy/security/make-credentials.sh DIR N); sets SWA_SECURITY_DIR",
           "the credentials directory (deploy/security/make-credentials.sh)");
  cli.text("--swarm", "NAME", o.swarm,
           "the swarm of this launch: every child's readers and writers in the DDS partition swa.NAME (SWA_SWARM), "
           "so another swarm or a stray publisher on the same domain never mixes with it. Default: $SWA_SWARM if "
           "set, else a new name per launch (printed), except with --secure (the credentials keep swarms apart). "
           "'none': the default partition (for a process started by hand, a bridge or a DDS tool to join the run)",
           "a swarm name, or none");
  const std::vector<std::string> vehicles{"direct", "px4", "ardupilot"};
  cli.choice(
      "--vehicle", "V", vehicles, [&o, vehicles](std::size_t k) { o.vehicle = vehicles[k]; },
      "how the agents reach their UAVs: direct (the simulator reads cmd_vel), px4 (each UAV a PX4 autopilot "
      "played by the simulator, one swa_px4_bridge --engage per agent, supervised like the agents; the release "
      "is vehicle.px4_release, default the newest) or ardupilot (each UAV an ArduPilot Copter, one "
      "swa_px4_bridge --autopilot ardupilot --engage per agent); the same as --set vehicle.interface=V");
  std::vector<std::string> namings;
  for (const auto n : {dds::Naming::kSwa, dds::Naming::kRos2}) namings.emplace_back(dds::namingName(n));
  cli.choice(
      "--naming", "N", namings, [&o, namings](std::size_t k) { o.naming = namings[k]; },
      "swa: topics swa/uav1/imu, types swa::msg::Imu; ros2: ROS 2's mapping (rt/swa/uav1/imu, "
      "swa_msgs::msg::dds_::Imu_) so ros2 topic list / echo / bag see the run (with --swarm none: ROS tools "
      "use the default partition). Sets SWA_NAMING for every child (default: $SWA_NAMING, else swa)");
  cli.text("--ros-namespace", "NS", o.ros_namespace,
           "with --naming ros2: a ROS namespace in front of every SWA topic (/NS/swa/uav1/imu), so two swarms can "
           "share a domain; sets SWA_ROS_NAMESPACE",
           "a ROS namespace");
  const std::vector<std::string> sets = recording::recordSetNames();
  cli.flagChoice(
      "--record", sets,
      [&o, sets](std::size_t k) {
        o.record = true;
        o.record_set = *recording::recordSetFromName(sets[k]);
      },
      "record each run into its directory's run.mcap (swa_monitor --record FILE --record-set SET). "
      "--record (= all): every topic's payloads unchanged, with their swa_msgs schemas, and the monitor's "
      "metrics; opens in Foxglove, Lichtblick, PlotJuggler; replays with swa_replay; costs the monitor "
      "what receiving every UAV's sensors costs. --record=monitor: only truth, events, the agents' states "
      "and the metrics, a small file at little cost, not replayable. A restarted monitor records into "
      "run_restart<K>.mcap");
  cli.text("--live", "[ADDR:]PORT", o.live,
           "watch the run while it flies: the monitor serves a live page and the Foxglove WebSocket protocol on this "
           "port (swa_monitor --live; 127.0.0.1 unless ADDR); the URL is printed",
           "[ADDR:]PORT");
  cli.footer(
      R"(Exit status: the monitor's verdict of the first run: 0 PASS (cohesive: d_NB within 5 % of r, no collision, one
group, no UAV on failsafe at the end), 1 FAIL, 3 INCOMPLETE (interrupted, timed out, or a process failed); 2 bad
arguments or scenario, or a missing executable (nothing started).)");
  return cli;
}

void finish(LaunchOptions& o, const app::Cli& cli, app::Problems& problems) {
  if (!o.swarm.empty() && o.swarm != "none") {
    if (const auto problem = dds::swarmNameProblem(o.swarm)) problems.push_back("--swarm " + *problem);
  }
  if (cli.given("--discovery-server")) {
    for (const std::string& p : dds::checkServerList(o.discovery_server))
      problems.push_back("--discovery-server: " + p);
  }
  if (o.restart_backoff_max_s < o.restart_backoff_s) {
    problems.push_back("--restart-backoff-max-s must not be below --restart-backoff-s");
  }
  if (cli.given("--ros-namespace")) {
    if (const auto problem = dds::rosNamespaceProblem(o.ros_namespace)) {
      problems.push_back("--ros-namespace " + *problem);
    }
    if (o.naming == "swa") problems.push_back("--ros-namespace needs the ros2 naming");
  }
  if (!o.discovery_server.empty() && o.transport != "discovery-server") {
    problems.push_back("--discovery-server needs --transport discovery-server");
  }
}

}  // namespace

std::optional<std::string> automaticTransport(const LaunchOptions& o, const char* env_transport, int uav_processes) {
  const bool asked = !o.transport.empty() || (env_transport != nullptr && *env_transport != '\0');
  if (asked || !o.secure_dir.empty() || !o.discovery_server.empty() ||
      uav_processes <= kMaxUavProcessesForSimpleDiscovery) {
    return std::nullopt;
  }
  return std::string("discovery-server");
}

double staggerOf(const LaunchOptions& o) {
  if (o.stagger_s) return *o.stagger_s;
  return o.secure_dir.empty() ? 0.0 : kSecureStaggerS;
}

LaunchOptions parseLaunchOptions(const std::vector<std::string>& args) {
  return app::parseOptions<LaunchOptions>(args, makeCli, finish);
}

std::string launchUsage() { return app::helpText(makeCli); }

}  // namespace swa::launch

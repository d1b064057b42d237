#include "launch_options.h"

#include <sstream>
#include <stdexcept>

#include "swa/dds/deployment.h"
#include "swa/dds/options.h"

namespace swa::launch {

LaunchOptions parseLaunchOptions(const std::vector<std::string>& args) {
  LaunchOptions o;
  std::vector<std::string> problems;
  dds::ArgWalker walker(args, problems);
  while (walker.next()) {
    const std::string& key = walker.key();
    const auto real = [&](double& out, double min, double max, const char* what) {
      if (const auto v = walker.value()) {
        if (const auto x = dds::parseReal(*v, min, max)) {
          out = *x;
        } else {
          problems.push_back(key + " '" + *v + "' is not " + what);
        }
      }
    };
    const auto text = [&](std::string& out, const char* what) {
      if (const auto v = walker.value()) {
        if (v->empty()) problems.push_back(key + " needs " + what);
        out = *v;
      }
    };
    if (key == "--help" || key == "-h") {
      o.help = true;
    } else if (key == "--scenario") {
      text(o.scenario_path, "a file name");
    } else if (key == "--set") {
      if (const auto v = walker.value()) o.overrides.push_back(*v);
    } else if (key == "--out") {
      text(o.out_dir, "a directory");
    } else if (key == "--bin-dir") {
      text(o.bin_dir, "a directory");
    } else if (key == "--domain") {
      if (const auto v = walker.value()) o.domain = *v;
    } else if (key == "--compare") {
      if (const auto v = walker.value()) {
        if (*v == "standalone") {
          o.compare = agent::Mode::kStandalone;
        } else if (*v == "swa") {
          o.compare = agent::Mode::kSwa;
        } else if (*v == "anchored") {
          o.compare = agent::Mode::kAnchored;
        } else {
          problems.push_back("--compare must be standalone, swa or anchored, got '" + *v + "'");
        }
      }
    } else if (key == "--max-restarts") {
      if (const auto v = walker.value()) {
        if (const auto n = dds::parseInteger(*v, 0, 1000)) {
          o.max_restarts = static_cast<int>(*n);
        } else {
          problems.push_back("--max-restarts '" + *v + "' is not a count in [0, 1000]");
        }
      }
    } else if (key == "--restart-backoff-s") {
      real(o.restart_backoff_s, 0.0, 600.0, "a delay in seconds in [0, 600]");
    } else if (key == "--restart-backoff-max-s") {
      real(o.restart_backoff_max_s, 0.0, 3600.0, "a delay in seconds in [0, 3600]");
    } else if (key == "--agent-timeout-s") {
      real(o.agent_timeout_s, 1e-3, 3600.0, "a timeout in seconds in [0.001, 3600]");
    } else if (key == "--timeout-s") {
      real(o.timeout_s, 0.0, 1e6, "a timeout in seconds in [0, 1e6] (0 = none)");
    } else if (key == "--grace-s") {
      real(o.grace_s, 0.0, 600.0, "a grace period in seconds in [0, 600]");
    } else if (key == "--transport") {
      if (const auto v = walker.value()) {
        if (dds::parseTransport(*v)) {
          o.transport = *v;
        } else {
          problems.push_back("--transport must be local, network or discovery-server, got '" + *v + "'");
        }
      }
    } else if (key == "--discovery-server") {
      if (const auto v = walker.value()) {
        for (const std::string& p : dds::checkServerList(*v)) problems.push_back("--discovery-server: " + p);
        o.discovery_server = *v;
      }
    } else if (key == "--discovery-port") {
      if (const auto v = walker.value()) {
        if (const auto n = dds::parseInteger(*v, 1024, 65535)) {
          o.discovery_port = static_cast<int>(*n);
        } else {
          problems.push_back("--discovery-port '" + *v + "' is not a port in [1024, 65535]");
        }
      }
    } else if (key == "--secure") {
      text(o.secure_dir, "the credentials directory (deploy/security/make-credentials.sh)");
    } else if (key == "--swarm") {
      text(o.swarm, "a swarm name, or none");
      if (o.swarm != "none" && !o.swarm.empty()) {
        if (const auto problem = dds::swarmNameProblem(o.swarm)) problems.push_back("--swarm " + *problem);
      }
    } else {
      problems.push_back("unknown argument '" + walker.raw() + "' (see --help)");
    }
  }
  if (o.scenario_path.empty() && !o.help && problems.empty()) problems.push_back("--scenario is required");
  if (o.restart_backoff_max_s < o.restart_backoff_s) {
    problems.push_back("--restart-backoff-max-s must not be below --restart-backoff-s");
  }
  if (!o.discovery_server.empty() && o.transport != "discovery-server") {
    problems.push_back("--discovery-server needs --transport discovery-server");
  }
  if (!problems.empty()) {
    std::ostringstream msg;
    for (std::size_t k = 0; k < problems.size(); ++k) msg << (k ? "\n" : "") << problems[k];
    throw std::invalid_argument(msg.str());
  }
  return o;
}

std::string launchUsage() {
  return R"(swa_launch: runs a scenario as processes: swa_sim, one swa_agent per UAV, and swa_monitor, on one DDS domain.

Usage: swa_launch --scenario FILE [--set key=value]... [--out DIR] [--compare standalone] [options]

What it does, per run:
  1. loads the scenario (with every --set) and stops here, exit 2, if anything is wrong with it;
  2. writes the effective scenario to DIR/scenario.yaml, the one file every child reads (no --set is passed on),
     and starts swa_monitor, the agents (swa_agent --id I --scenario DIR/scenario.yaml) and swa_sim (which waits
     until all of them are discovered);
  3. supervises: an agent that dies while the scenario runs is restarted after a back-off (0.5 s, doubling per
     restart of that agent, at most 8 s; at most --max-restarts times), and every restart is appended to
     DIR/logs/restarts.csv, which the monitor puts into the report;
  4. when the simulator finishes, waits for the monitor's verdict, stops the agents, removes the shared-memory
     files of killed processes, and exits with the verdict.
Each child's output goes to DIR/logs/<name>.log (agent_<I>.log, sim.log, monitor.log). SIGINT / SIGTERM are
forwarded: the simulator ends the run early, the monitor writes what it has, everything is stopped and reaped.

With --compare MODE, the same scenario and seed run a second time with agent.mode = MODE (e.g. standalone, the
paper's baseline) into DIR/<mode>/, the first run into DIR/<scenario mode>/, and DIR/report.html shows both side by
side. Without it the run's files are in DIR itself.

Options:
  --scenario FILE           scenario YAML (see deploy/scenarios/, swa_sim --parameters)
  --set key=value           override a scenario key, e.g. --set duration_s=60 --set uav_count=12 (repeatable)
  --out DIR                 output directory (default out/launch)
  --compare MODE            standalone | swa | anchored: also run the baseline in that mode (same seed)
  --domain D                DDS domain id 0..232 (default: $SWA_DOMAIN, else 0); use distinct domains for
                            launches that run at the same time
  --bin-dir DIR             where swa_sim, swa_agent, swa_monitor are (default: next to swa_launch)
  --max-restarts N          restarts per agent and run (default 5)
  --restart-backoff-s T     first restart delay (default 0.5)
  --restart-backoff-max-s T back-off cap (default 8)
  --agent-timeout-s T       lockstep: an agent silent this long is declared dead by the simulator (default 2)
  --timeout-s T             wall-clock bound per run; the run is then stopped like on SIGINT (default 0 = none)
  --grace-s T               how long a stopped child may take before it is killed (default 10)
  --transport T             local (default: shared memory + UDP, one host) | network (UDPv4 only, multicast
                            discovery) | discovery-server (UDPv4, discovery through a Fast DDS Discovery Server);
                            sets SWA_TRANSPORT for every child (deploy/README.md: when to use which)
  --discovery-server LIST   with discovery-server: the servers' IP:PORT[;IP:PORT...]; without it swa_launch starts
                            one (fast-discovery-server -i 0) on 127.0.0.1:--discovery-port and stops it at the end
  --discovery-port P        port of the server swa_launch starts (default 11811)
  --secure DIR              DDS Security: authenticated, encrypted, per-UAV permissions, with the credentials in
                            DIR (create them with deploy/security/make-credentials.sh DIR N); sets SWA_SECURITY_DIR
  --swarm NAME              the swarm of this launch: every child's readers and writers in the DDS partition
                            swa.NAME (SWA_SWARM), so another swarm or a stray publisher on the same domain never
                            mixes with it. Default: $SWA_SWARM if set, else a new name per launch (printed), except
                            with --secure (the credentials keep swarms apart). 'none': the default partition (for
                            a process started by hand, a bridge or a DDS tool to join the run)
  -h, --help                this text

Exit status: the monitor's verdict of the first run: 0 PASS (cohesive: d_NB within 5 % of r, no collision, one
group), 1 FAIL, 3 INCOMPLETE (interrupted, timed out, or a process failed); 2 bad arguments or scenario, or a
missing executable (nothing started).
)";
}

}  // namespace swa::launch

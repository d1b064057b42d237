#include "sim_options.h"

#include <sstream>
#include <stdexcept>

#include "swa/dds/deployment.h"
#include "swa/dds/options.h"

namespace swa::sim_node {

SimOptions parseSimOptions(const std::vector<std::string>& args) {
  SimOptions o;
  std::vector<std::string> problems;
  dds::ArgWalker walker(args, problems);
  while (walker.next()) {
    const std::string& key = walker.key();
    const auto value = [&walker] { return walker.value(); };
    const auto real = [&](double& out, double min, double max, const char* what) {
      if (const auto v = value()) {
        if (const auto x = dds::parseReal(*v, min, max)) {
          out = *x;
        } else {
          problems.push_back(key + " '" + *v + "' is not " + what);
        }
      }
    };
    const auto path = [&](std::string& out) {
      if (const auto v = value()) {
        if (v->empty()) problems.push_back(key + " needs a file name");
        out = *v;
      }
    };
    if (key == "--help" || key == "-h") {
      o.help = true;
    } else if (key == "--parameters") {
      o.list_parameters = true;
    } else if (key == "--scenario") {
      path(o.scenario_path);
    } else if (key == "--set") {
      if (const auto v = value()) o.overrides.push_back(*v);
    } else if (key == "--domain") {
      if (const auto v = value()) o.domain = *v;
    } else if (key == "--agent-timeout-s") {
      real(o.agent_timeout_s, 1e-3, 3600.0, "a timeout in seconds in [0.001, 3600]");
    } else if (key == "--startup-timeout-s") {
      real(o.startup_timeout_s, 0.0, 3600.0, "a timeout in seconds in [0, 3600]");
    } else if (key == "--truth-every") {
      if (const auto v = value()) {
        if (const auto n = dds::parseInteger(*v, 1, 1'000'000)) {
          o.truth_every = static_cast<int>(*n);
        } else {
          problems.push_back("--truth-every '" + *v + "' is not a step count in [1, 1000000]");
        }
      }
    } else if (key == "--wait-monitors") {
      if (const auto v = value()) {
        if (const auto n = dds::parseInteger(*v, 0, 64)) {
          o.wait_monitors = static_cast<int>(*n);
        } else {
          problems.push_back("--wait-monitors '" + *v + "' is not a count in [0, 64]");
        }
      }
    } else if (key == "--truth-out") {
      path(o.truth_out);
    } else if (key == "--summary-out") {
      path(o.summary_out);
    } else if (key == "--export-agent-config") {
      path(o.export_agent_config);
    } else {
      problems.push_back("unknown argument '" + walker.raw() + "' (see --help)");
    }
  }
  if (o.scenario_path.empty() && !o.help && !o.list_parameters && problems.empty()) {
    problems.push_back("--scenario is required");
  }
  if (!problems.empty()) {
    std::ostringstream msg;
    for (std::size_t k = 0; k < problems.size(); ++k) msg << (k ? "\n" : "") << problems[k];
    throw std::invalid_argument(msg.str());
  }
  return o;
}

std::string simUsage() {
  return R"(swa_sim: the simulated world of a scenario as a Fast DDS process (the swarm's agents are swa_agent processes).

Usage: swa_sim --scenario FILE [--set key=value]... [--domain D] [--agent-timeout-s T] [options]

Publishes  swa/uav<i>/imu, swa/uav<i>/detections, swa/uav<i>/gnss   (each UAV's own sensors)
           swa/truth (ground truth, monitor only), swa/events, swa/clock
Reads      swa/uav<i>/cmd_vel

Clock (scenario key clock.mode):
  lockstep  (default) publish the sensor samples of step k, wait until every live agent answered step k's IMU
            sample, apply the commands, step. An agent silent for --agent-timeout-s is declared dead
            (EVENT_AGENT_DEAD; its UAV falls back to the failsafe) and rejoins (EVENT_AGENT_REJOINED) when it
            answers again. Deterministic: same scenario and seed, same run as swa_batch.
  realtime  wall-clock pacing at clock.speed; the latest setpoint of each UAV is applied as it arrives. The
            clock starts once every agent has answered step 0 (or after --startup-timeout-s). A command is
            late when it arrives after the UAV's next IMU sample is due (one step period), missing when it
            never arrives; both are counted in the summary and the last line on stderr.
Before the first step the simulator waits until every agent's endpoints are discovered (--startup-timeout-s).
At the end it publishes EVENT_SCENARIO_END and exits 0.

Options:
  --scenario FILE           scenario YAML (see deploy/scenarios/, swa_sim --parameters)
  --set key=value           override a scenario key, e.g. --set duration_s=20 --set mps.fov_deg=240 (repeatable)
  --domain D                DDS domain id 0..232 (default: $SWA_DOMAIN, else 0)
  --agent-timeout-s T       lockstep: wall seconds to wait for an agent's answer (default 2)
  --startup-timeout-s T     wall seconds to wait for discovery of every agent (default 60)
  --wait-monitors N         also wait until N readers of swa/truth and swa/events are discovered, so a monitor
                            sees the run from step 0 (default 0; swa_launch passes 1)
  --truth-every N           publish swa/truth every N steps and at the last step (default 10)
  --truth-out FILE          also write every published truth sample to FILE (CSV, one row per UAV)
  --summary-out FILE        write a JSON summary of the run (steps, collisions, dead agents, wall time, loop
                            latency: p50/p99/max wall time from publishing an IMU sample to receiving the
                            cmd_vel that answers it, and, in realtime, late commands and missing answers)
  --export-agent-config FILE  write the agent configuration the scenario implies (YAML for swa_agent --config)
                            and exit without starting DDS
  --parameters              list every scenario parameter and exit
  -h, --help                this text

Exit status: 0 scenario completed; 1 DDS failure, discovery timeout or interrupted by a signal;
             2 bad arguments or scenario (nothing started).

)" + dds::environmentHelp();
}

}  // namespace swa::sim_node

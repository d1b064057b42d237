#include "sim_options.h"

#include <cstdlib>

#include "swa/app/cli.h"
#include "swa/dds/deployment.h"
#include "swa/dds/options.h"

namespace swa::sim_node {
namespace {

app::Cli makeCli(SimOptions& o) {
  app::Cli cli("swa_sim",
               "the simulated world of a scenario as a Fast DDS process (the swarm's agents are swa_agent processes).");
  cli.usage("swa_sim --scenario FILE [--set key=value]... [--domain D] [--agent-timeout-s T] [options]");
  cli.details(R"(Publishes  swa/uav<i>/sensors: each UAV's own sensors of one step (IMU sample, detections, GNSS fix)
             in one SensorFrame; with SWA_SENSOR_FRAMES=0, an autopilot vehicle, other detection messages
             or SWA_NAMING=ros2 each on its own topic: swa/uav<i>/imu, swa/uav<i>/detections, swa/uav<i>/gnss
           swa/truth (ground truth, monitor only), swa/events, swa/clock
Reads      swa/uav<i>/cmd_vel

Clock (scenario key clock.mode):
  lockstep  (default) publish the sensor samples of step k, wait until every live agent answered step k's IMU
            sample, apply the commands, step. An agent silent for --agent-timeout-s is declared dead
            (EVENT_AGENT_DEAD; its UAV falls back to the failsafe) and rejoins (EVENT_AGENT_REJOINED) when it
            answers again. Deterministic: same scenario and seed, same run as swa_batch.
  realtime  wall-clock pacing at clock.speed; the latest setpoint of each UAV is applied as it arrives. The
            clock starts once every agent has answered step 0 (or after --startup-timeout-s). A command is
            late when it misses the step it answers: it arrives after the UAV's next IMU sample is due (one
            step period) and after the simulator has taken that step (when the simulator is late itself);
            missing when it never arrives; both are counted in the summary and the last line on stderr.
Before the first step the simulator waits until every agent's endpoints are discovered (--startup-timeout-s).
At the end it publishes EVENT_SCENARIO_END and exits 0.)");
  cli.scenario(o.scenario_path, "scenario YAML (see deploy/scenarios/, swa_sim --parameters)");
  cli.required("--scenario");
  cli.overrides(o.overrides, "override a scenario key, e.g. --set duration_s=20 --set mps.fov_deg=240");
  cli.domain(o.domain, dds::kMaxDomainId);
  cli.real("--agent-timeout-s", "T", o.agent_timeout_s, 1e-3, 3600.0, "a timeout in seconds",
           "lockstep: wall seconds to wait for an agent's answer");
  if (const char* security = std::getenv("SWA_SECURITY_DIR"); security != nullptr && *security != '\0') {
    o.startup_timeout_s = kSecureStartupTimeoutS;
  }
  cli.real("--startup-timeout-s", "T", o.startup_timeout_s, 0.0, 3600.0, "a timeout in seconds",
           "wall seconds to wait for discovery of every agent (120 with DDS Security on, SWA_SECURITY_DIR: a stalled "
           "handshake or a stuck participant's restart needs the room)");
  cli.integer("--wait-monitors", "N", o.wait_monitors, 0, 64, "a count",
              "also wait until N readers of swa/truth and swa/events are discovered, so a monitor sees the run "
              "from step 0; swa_launch passes 1");
  cli.integer("--truth-every", "N", o.truth_every, 1, 1'000'000, "a step count",
              "publish swa/truth every N steps and at the last step");
  cli.path("--truth-out", "FILE", o.truth_out,
           "also write every published truth sample to FILE (CSV, one row per UAV)");
  cli.path("--summary-out", "FILE", o.summary_out,
           "write a JSON summary of the run (steps, collisions, dead agents, wall time, loop latency: p50/p99/max "
           "wall time from publishing an IMU sample to receiving the cmd_vel that answers it, and, in realtime, "
           "late commands and missing answers)");
  cli.path("--export-agent-config", "FILE", o.export_agent_config,
           "write the agent configuration the scenario implies (YAML for swa_agent --config) and exit without "
           "starting DDS");
  cli.answer("--parameters", o.list_parameters, "list every scenario parameter and exit");
  cli.footer(R"(Exit status: 0 scenario completed; 1 DDS failure, discovery timeout or interrupted by a signal;
             2 bad arguments or scenario (nothing started); 70 Fast DDS stuck inside its participant (deleting
             it took over 12 s).

)" + dds::environmentHelp());
  return cli;
}

}  // namespace

SimOptions parseSimOptions(const std::vector<std::string>& args) { return app::parseOptions(args, makeCli); }

std::string simUsage() { return app::helpText(makeCli); }

}  // namespace swa::sim_node

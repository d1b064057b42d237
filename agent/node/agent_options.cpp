#include "agent_options.h"

#include "swa/app/cli.h"
#include "swa/dds/deployment.h"
#include "swa/dds/options.h"

namespace swa::agent_node {
namespace {

app::Cli makeCli(AgentOptions& o) {
  app::Cli cli("swa_agent", "the SWA agent of one UAV as a Fast DDS process.");
  cli.usage("swa_agent --id I [--config FILE] [--set key=value]... [--domain D]");
  cli.details(R"(Reads only   swa/uav<I>/sensors (a step's samples in one SensorFrame, from swa_sim) and
             swa/uav<I>/imu, swa/uav<I>/detections, swa/uav<I>/gnss (the same samples one by one)
             swa/swarm/mission  (the ground's mission, from swa_mission: one writer, flown from the next IMU sample)
Writes only  swa/uav<I>/cmd_vel (one VelocitySetpoint per IMU sample, echoing its stamp and seq)
             swa/uav<I>/state   (AgentState diagnostics, 10 Hz of sample time))");
  cli.integer("--id", "I", o.id, 0, kMaxUavId, "a UAV id", "UAV index; participant name swa_agent_<I>");
  cli.required("--id");
  cli.path("--config", "FILE", o.config_path,
           "agent parameters (YAML, layout of deploy/config/agent.yaml); default: built-in defaults. "
           "swa_launch writes its run's as DIR/agent.yaml; `swa_sim --scenario S --export-agent-config FILE` "
           "writes the one a scenario implies.");
  cli.overrides(o.overrides, "override one parameter, e.g. --set formation.radius_m=12");
  cli.domain(o.domain, dds::kMaxDomainId);
  cli.answer("--parameters", o.list_parameters, "list every agent parameter (key, unit, bounds, default) and exit");
  cli.footer(R"(Runs until SIGINT or SIGTERM, then deletes its DDS entities and exits 0.
One agent per UAV and swarm: when another swa_agent with the same --id runs in the same swarm (SWA_SWARM) on the
domain, the one started later refuses to run (exit 3) and the other logs it.
Exit status: 0 stopped by a signal; 1 DDS failure (also: security credentials refused); 2 bad arguments or
             configuration (nothing started); 3 refused: an older agent with this --id runs in this swarm; 70 Fast
             DDS stuck inside its participant (deleting it took over 12 s): restart the agent.

)" + dds::environmentHelp());
  return cli;
}

}  // namespace

AgentOptions parseAgentOptions(const std::vector<std::string>& args) {
  return app::parseOptions<AgentOptions>(
      args, makeCli, [&args](const AgentOptions&, const app::Cli&, app::Problems& p) {
        // The agent reads its own configuration, not the scenario around it (issue #47): say where that file comes
        // from.
        for (const std::string& a : args) {
          if (a == "--scenario" || a.rfind("--scenario=", 0) == 0) {
            p.push_back(
                "swa_agent takes --config FILE, not a scenario: swa_launch writes its run's DIR/agent.yaml, and "
                "`swa_sim --scenario S --export-agent-config FILE` writes the one a scenario implies");
          }
        }
      });
}

std::string agentUsage() { return app::helpText(makeCli); }

}  // namespace swa::agent_node

// swa_sim: the simulated world as a Fast DDS process. See --help (sim_options.cpp).

#include <cstdio>
#include <fstream>
#include <memory>
#include <stdexcept>

#include "sim_node.h"
#include "sim_options.h"
#include "swa/agent/config_io.h"
#include "swa/app/program.h"
#include "swa/dds/options.h"
#include "swa/sim/scenario_io.h"

namespace swa::sim_node {
namespace {

app::Plan prepare(const std::vector<std::string>& args) {
  const SimOptions options = parseSimOptions(args);
  if (auto done = app::printIf(options.help, simUsage, options.list_parameters, sim::describeScenarioParameters)) {
    return *done;
  }
  const sim::Scenario scenario = sim::loadScenario(options.scenario_path, options.overrides);
  if (!options.export_agent_config.empty()) {
    std::ofstream out(options.export_agent_config);
    out << "# Agent configuration implied by " << options.scenario_path << " (written by swa_sim)\n"
        << agent::toYaml(scenario.agent);
    if (!out.flush()) throw std::runtime_error("cannot write --export-agent-config " + options.export_agent_config);
    return app::exitWith(0);
  }
  const int domain = dds::resolveDomain(options.domain);
  // Written at the end; a path that cannot be written is found now, before anything starts.
  if (!options.summary_out.empty() && !std::ofstream(options.summary_out)) {
    throw std::runtime_error("cannot write --summary-out " + options.summary_out);
  }
  return app::startWith([options, scenario, domain]() -> std::unique_ptr<app::Role> {
    return std::make_unique<SimNode>(scenario, options, domain, dds::resolveProfilesFile());
  });
}

}  // namespace
}  // namespace swa::sim_node

int main(int argc, char** argv) {
  return swa::app::runProgram("swa_sim", "scenario", argc, argv, swa::sim_node::prepare);
}

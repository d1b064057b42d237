// swa_sim: the simulated world as a Fast DDS process. See --help (sim_options.cpp).

#include <cstdio>
#include <exception>
#include <fstream>
#include <string>
#include <vector>

#include "sim_node.h"
#include "sim_options.h"
#include "swa/agent/config_io.h"
#include "swa/dds/options.h"
#include "swa/dds/participant.h"
#include "swa/dds/shutdown.h"
#include "swa/sim/scenario_io.h"

// Fast DDS declares a global `namespace dds = eprosima::fastdds::dds;`: stay inside namespace swa so `dds::` is ours.
namespace swa::sim_node {
namespace {

int simMain(int argc, char** argv) {
  // Everything that can be wrong with the arguments or the scenario is found before any DDS entity exists.
  SimOptions options;
  sim::Scenario scenario;
  int domain = 0;
  std::ofstream summary_file;
  try {
    options = parseSimOptions(std::vector<std::string>(argv + 1, argv + argc));
    if (options.help) {
      std::fputs(simUsage().c_str(), stdout);
      return 0;
    }
    if (options.list_parameters) {
      std::fputs(sim::describeScenarioParameters().c_str(), stdout);
      return 0;
    }
    scenario = sim::loadScenario(options.scenario_path, options.overrides);
    if (!options.export_agent_config.empty()) {
      std::ofstream out(options.export_agent_config);
      out << "# Agent configuration implied by " << options.scenario_path << " (written by swa_sim)\n"
          << agent::toYaml(scenario.agent);
      if (!out.flush()) throw std::runtime_error("cannot write --export-agent-config " + options.export_agent_config);
      return 0;
    }
    domain = dds::resolveDomain(options.domain);
    if (!options.summary_out.empty()) {
      summary_file.open(options.summary_out);
      if (!summary_file) throw std::runtime_error("cannot write --summary-out " + options.summary_out);
    }
  } catch (const params::ConfigError& e) {
    std::fprintf(stderr, "swa_sim: invalid scenario:\n%s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "swa_sim: %s\n(see swa_sim --help)\n", e.what());
    return 2;
  }

  dds::installShutdownHandlers();
  try {
    SimNode node(scenario, options, domain, dds::resolveProfilesFile());
    dds::acceptShutdownSignals();
    const int status = node.run();
    if (summary_file.is_open()) {
      summary_file << node.summaryJson();
      summary_file.flush();
    }
    return status;
  } catch (const dds::DdsError& e) {
    std::fprintf(stderr, "swa_sim: DDS error: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "swa_sim: %s\n", e.what());
    return 1;
  }
}

}  // namespace
}  // namespace swa::sim_node

int main(int argc, char** argv) { return swa::sim_node::simMain(argc, argv); }

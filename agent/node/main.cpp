// swa_agent: one UAV's agent as a Fast DDS process. See --help (agent_options.cpp).

#include <cstdio>
#include <memory>

#include "agent_node.h"
#include "agent_options.h"
#include "swa/agent/config_io.h"
#include "swa/app/program.h"
#include "swa/dds/options.h"

namespace swa::agent_node {
namespace {

app::Plan prepare(const std::vector<std::string>& args) {
  const AgentOptions options = parseAgentOptions(args);
  if (auto done = app::printIf(options.help, agentUsage, options.list_parameters, agent::describeParameters)) {
    return *done;
  }
  agent::AgentConfig config;
  if (!options.config_path.empty()) config = agent::loadAgentConfig(options.config_path);
  config = agent::applyOverrides(config, options.overrides);
  const int domain = dds::resolveDomain(options.domain);
  return app::startWith([options, config, domain]() -> std::unique_ptr<app::Role> {
    const std::string profiles = dds::resolveProfilesFile();
    auto node = std::make_unique<AgentNode>(options.id, config, domain, profiles);
    std::fprintf(stderr, "swa_agent %d: up on domain %d (mode %s, neighbourhood %s), profiles %s\n", options.id, domain,
                 agent::toString(config.mode).c_str(), agent::toString(config.formation.neighbourhood).c_str(),
                 profiles.c_str());
    return node;
  });
}

}  // namespace
}  // namespace swa::agent_node

int main(int argc, char** argv) {
  return swa::app::runProgram("swa_agent", "configuration", argc, argv, swa::agent_node::prepare);
}

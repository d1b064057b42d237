// swa_agent: one UAV's agent as a Fast DDS process. See --help (agent_options.cpp).

#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "agent_node.h"
#include "agent_options.h"
#include "swa/agent/config_io.h"
#include "swa/dds/options.h"
#include "swa/dds/participant.h"
#include "swa/dds/shutdown.h"
#include "swa/sim/scenario_io.h"

// Fast DDS declares a global `namespace dds = eprosima::fastdds::dds;`: stay inside namespace swa so `dds::` is ours.
namespace swa::agent_node {
namespace {

int agentMain(int argc, char** argv) {
  // Everything that can be wrong with the arguments or the configuration is found before any DDS entity exists.
  AgentOptions options;
  agent::AgentConfig config;
  int domain = 0;
  try {
    options = parseAgentOptions(std::vector<std::string>(argv + 1, argv + argc));
    if (options.help) {
      std::fputs(agentUsage().c_str(), stdout);
      return 0;
    }
    if (options.list_parameters) {
      std::fputs(agent::describeParameters().c_str(), stdout);
      return 0;
    }
    if (!options.config_path.empty()) config = agent::loadAgentConfig(options.config_path);
    if (!options.scenario_path.empty()) config = sim::loadScenario(options.scenario_path).agent;
    config = agent::applyOverrides(config, options.overrides);
    domain = dds::resolveDomain(options.domain);
  } catch (const agent::ConfigError& e) {
    std::fprintf(stderr, "swa_agent: invalid configuration:\n%s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "swa_agent: %s\n(see swa_agent --help)\n", e.what());
    return 2;
  }

  dds::installShutdownHandlers();
  const std::string profiles = dds::resolveProfilesFile();
  try {
    AgentNode node(options.id, config, domain, profiles);
    std::fprintf(stderr, "swa_agent %d: up on domain %d (mode %s, neighbourhood %s), profiles %s\n", options.id,
                 domain, agent::toString(config.mode).c_str(), agent::toString(config.formation.neighbourhood).c_str(),
                 profiles.c_str());
    dds::acceptShutdownSignals();
    const int status = node.run();
    if (status == AgentNode::kExitTwin) return status;  // refuseAsTwin() said why
    const AgentNodeStats& s = node.stats();
    std::fprintf(stderr,
                 "swa_agent %d: stopping on signal %d after %llu IMU, %llu detection, %llu GNSS samples; %llu commands, "
                 "%llu states, %llu foreign samples, %llu write failures\n",
                 options.id, dds::shutdownSignal(), static_cast<unsigned long long>(s.imu),
                 static_cast<unsigned long long>(s.detections), static_cast<unsigned long long>(s.gnss),
                 static_cast<unsigned long long>(s.commands), static_cast<unsigned long long>(s.states),
                 static_cast<unsigned long long>(s.foreign), static_cast<unsigned long long>(s.write_failures));
    // Where the agent stood at the end: a supervisor (or a person reading the log) sees whether it was flying
    // relative to its neighbours when it stopped.
    const agent::Diagnostics& d = node.diagnostics();
    const char* stage = d.stage == agent::Stage::kTracking ? "tracking" : d.stage == agent::Stage::kLost ? "lost"
                                                                                                        : "initializing";
    std::fprintf(stderr, "swa_agent %d: final stage %s, %d confirmed track(s), frame fitted on %d neighbour(s)\n",
                 options.id, stage, d.confirmed_tracks, d.neighbour_count);
    const agent::RejectCounters& r = d.rejected;
    std::fprintf(stderr,
                 "swa_agent %d: inputs rejected: %llu non-finite, %llu out of order, %llu future stamp, %llu oversize, "
                 "%llu bad id, %llu implausible, %llu before a heading; %llu stamp resync(s), %llu forced release(s) "
                 "from the stamp orderer, %llu replayed sample(s) dropped after a reconnection\n",
                 options.id, static_cast<unsigned long long>(r.nonfinite),
                 static_cast<unsigned long long>(r.out_of_order), static_cast<unsigned long long>(r.future),
                 static_cast<unsigned long long>(r.oversize), static_cast<unsigned long long>(r.bad_id),
                 static_cast<unsigned long long>(r.implausible), static_cast<unsigned long long>(r.no_heading),
                 static_cast<unsigned long long>(d.stamp_resyncs), static_cast<unsigned long long>(s.forced_releases),
                 static_cast<unsigned long long>(s.replayed));
    return status;
  } catch (const dds::DdsError& e) {
    std::fprintf(stderr, "swa_agent %d: DDS error: %s\n", options.id, e.what());
    return 1;
  }
}

}  // namespace
}  // namespace swa::agent_node

int main(int argc, char** argv) { return swa::agent_node::agentMain(argc, argv); }

#pragma once
// The live view's channels (swa_monitor --live): what the monitor knows at each truth sample and agent state, as JSON
// messages with their JSON Schemas, for Foxglove's panels and the page at "/". Metrics use the recording's channel
// (step_metrics_json.h). No I/O.
//
//   /swa/live/swarm        swa_live/Swarm       per truth sample: every UAV's position and velocity (world frame,
//                                               x east, y north), the neighbour links the agents fitted their
//                                               floating frames on, and each agent's floating-frame centre
//   /swa/live/uav<I>/state swa_live/AgentState  per state of agent I: its estimate in its floating frame

#include <map>
#include <string>
#include <utility>
#include <vector>

#include "monitor_inputs.h"

namespace swa::live {

constexpr const char* kSwarmTopic = "/swa/live/swarm";
constexpr const char* kSwarmSchemaName = "swa_live/Swarm";
constexpr const char* kAgentStateSchemaName = "swa_live/AgentState";
std::string agentStateTopic(int uav);

std::string swarmJsonSchema();
std::string agentStateJsonSchema();

// The swarm at one truth sample: what /swa/live/swarm says and the swarm picture (live_pictures.h) shows.
struct SwarmScene {
  struct Uav {
    int id = 0;
    double x_m = 0.0;  // world frame, x east, y north
    double y_m = 0.0;
    double vx_mps = 0.0;
    double vy_mps = 0.0;
    bool agent_alive = true;
  };
  struct Centre {
    int uav = 0;
    double x_m = 0.0;
    double y_m = 0.0;
  };
  double t_s = 0.0;
  std::vector<Uav> uavs;
  std::vector<std::pair<int, int>> links;  // (a, b) with a < b, each once, ascending
  std::vector<Centre> centres;             // by agent id
};

// `latest`: each agent's newest state (its estimate gives the links and the centre: the centre of agent i's floating
// frame in the world is its true position minus its estimated position in that frame).
SwarmScene swarmScene(const monitor_node::TruthSample& truth, const std::map<int, monitor_node::StateSample>& latest);
std::string swarmJson(const SwarmScene& scene);
std::string agentStateJson(const monitor_node::StateSample& state);

}  // namespace swa::live

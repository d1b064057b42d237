#include "live_messages.h"

#include <cmath>
#include <set>
#include <utility>

#include <nlohmann/json.hpp>

namespace swa::live {
namespace {

using Json = nlohmann::ordered_json;

Json number(double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); }

Json numberSchema(const char* meaning) { return {{"type", Json::array({"number", "null"})}, {"description", meaning}}; }

}  // namespace

std::string agentStateTopic(int uav) { return "/swa/live/uav" + std::to_string(uav) + "/state"; }

std::string swarmJsonSchema() {
  const Json uav = {{"type", "object"},
                    {"properties",
                     {{"id", {{"type", "integer"}}},
                      {"x_m", numberSchema("east [m]")},
                      {"y_m", numberSchema("north [m]")},
                      {"vx_mps", numberSchema("[m/s]")},
                      {"vy_mps", numberSchema("[m/s]")},
                      {"agent_alive", {{"type", "boolean"}}}}},
                    {"required", {"id", "x_m", "y_m", "vx_mps", "vy_mps", "agent_alive"}}};
  const Json centre = {
      {"type", "object"},
      {"properties",
       {{"uav", {{"type", "integer"}}}, {"x_m", numberSchema("east [m]")}, {"y_m", numberSchema("north [m]")}}},
      {"required", {"uav", "x_m", "y_m"}}};
  const Json schema = {
      {"title", kSwarmSchemaName},
      {"description",
       "the swarm at one truth sample: UAVs (world frame, x east, y north), the neighbour links the "
       "agents fitted their floating frames on, each agent's floating-frame centre in the world"},
      {"type", "object"},
      {"properties",
       {{"t_s", {{"type", "number"}, {"description", "simulated time [s]"}}},
        {"uavs", {{"type", "array"}, {"items", uav}}},
        {"links", {{"type", "array"}, {"items", {{"type", "array"}, {"items", {{"type", "integer"}}}}}}},
        {"centres", {{"type", "array"}, {"items", centre}}}}},
      {"required", {"t_s", "uavs", "links", "centres"}}};
  return schema.dump();
}

std::string agentStateJsonSchema() {
  const Json schema = {{"title", kAgentStateSchemaName},
                       {"description", "one agent's state: its estimate in its floating frame"},
                       {"type", "object"},
                       {"properties",
                        {{"t_s", {{"type", "number"}}},
                         {"uav", {{"type", "integer"}}},
                         {"mode", {{"type", "string"}}},
                         {"valid", {{"type", "boolean"}, {"description", "a tracked floating-frame estimate"}}},
                         {"x_m", numberSchema("own position in the floating frame [m]")},
                         {"y_m", numberSchema("[m]")},
                         {"vx_mps", numberSchema("own velocity relative to the floating frame [m/s]")},
                         {"vy_mps", numberSchema("[m/s]")},
                         {"neighbours", {{"type", "array"}, {"items", {{"type", "integer"}}}}}}},
                       {"required", {"t_s", "uav", "mode", "valid", "x_m", "y_m", "vx_mps", "vy_mps", "neighbours"}}};
  return schema.dump();
}

SwarmScene swarmScene(const monitor_node::TruthSample& truth, const std::map<int, monitor_node::StateSample>& latest) {
  SwarmScene scene;
  scene.t_s = monitor_node::stampSeconds(truth.stamp_ns);
  std::map<int, const monitor::UavTruth*> by_id;
  for (std::size_t k = 0; k < truth.uavs.size(); ++k) {
    const monitor::UavTruth& u = truth.uavs[k];
    by_id[u.id] = &u;
    scene.uavs.push_back({u.id, u.position_m.x(), u.position_m.y(), u.velocity_mps.x(), u.velocity_mps.y(),
                          k < truth.agent_alive.size() ? static_cast<bool>(truth.agent_alive[k]) : true});
  }
  std::set<std::pair<int, int>> links;
  for (const auto& [uav, state] : latest) {
    const monitor::EstimateRecord& e = state.estimate;
    const auto self = by_id.find(uav);
    if (!e.valid || self == by_id.end()) continue;
    for (int n = 0; n < e.neighbour_count; ++n) {
      const int other = e.neighbour_ids[static_cast<std::size_t>(n)];
      if (other != uav && by_id.count(other) > 0) links.emplace(std::min(uav, other), std::max(uav, other));
    }
    const agent::Vec2 centre = self->second->position_m - e.position_m;
    scene.centres.push_back({uav, centre.x(), centre.y()});
  }
  scene.links.assign(links.begin(), links.end());
  return scene;
}

std::string swarmJson(const SwarmScene& scene) {
  Json uavs = Json::array();
  for (const SwarmScene::Uav& u : scene.uavs) {
    uavs.push_back({{"id", u.id},
                    {"x_m", number(u.x_m)},
                    {"y_m", number(u.y_m)},
                    {"vx_mps", number(u.vx_mps)},
                    {"vy_mps", number(u.vy_mps)},
                    {"agent_alive", u.agent_alive}});
  }
  Json centres = Json::array();
  for (const SwarmScene::Centre& c : scene.centres) {
    centres.push_back({{"uav", c.uav}, {"x_m", number(c.x_m)}, {"y_m", number(c.y_m)}});
  }
  Json link_list = Json::array();
  for (const auto& [a, b] : scene.links) link_list.push_back({a, b});
  const Json j = {{"t_s", scene.t_s}, {"uavs", uavs}, {"links", link_list}, {"centres", centres}};
  return j.dump();
}

std::string agentStateJson(const monitor_node::StateSample& state) {
  const monitor::EstimateRecord& e = state.estimate;
  Json neighbours = Json::array();
  for (int n = 0; n < e.neighbour_count; ++n) neighbours.push_back(e.neighbour_ids[static_cast<std::size_t>(n)]);
  const Json j = {{"t_s", monitor_node::stampSeconds(state.stamp_ns)},
                  {"uav", state.uav},
                  {"mode", state.mode ? agent::toString(*state.mode) : std::string("unknown")},
                  {"valid", e.valid},
                  {"x_m", e.valid ? number(e.position_m.x()) : Json(nullptr)},
                  {"y_m", e.valid ? number(e.position_m.y()) : Json(nullptr)},
                  {"vx_mps", e.valid ? number(e.velocity_mps.x()) : Json(nullptr)},
                  {"vy_mps", e.valid ? number(e.velocity_mps.y()) : Json(nullptr)},
                  {"neighbours", neighbours}};
  return j.dump();
}

}  // namespace swa::live

#pragma once
// The "no inter-agent communication" audit (DESIGN §1): given every reader and writer seen on a domain, which agent
// endpoints break the rule that agent I reads only swa/uav<I>/{imu,detections,gnss,sensors} (and swa/clock, and the
// ground's swa/swarm/mission, which no agent writes) and
// writes only swa/uav<I>/{cmd_vel,state}. Pure, no DDS include: test_isolation feeds it what Fast DDS discovery
// reported, test_isolation_audit feeds it synthetic lists (including planted violations, so the audit is known to
// fail).
//
// An agent is a participant named swa_agent_<I> (agent/node/agent_node.cpp). Participants are told apart by GUID
// prefix, not by name, so two processes claiming the same name are still audited against each other.

#include <algorithm>
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "swa/dds/topics.h"

namespace swa::testing {

enum class EndpointKind { kReader, kWriter };

struct Endpoint {
  EndpointKind kind = EndpointKind::kReader;
  std::string participant;       // the name the participant announced; empty if its announcement was never seen
  std::string participant_guid;  // GUID prefix of the participant, as text
  std::string topic;
  std::string type;
};

constexpr const char* kAgentNamePrefix = "swa_agent_";
constexpr const char* kBridgeNamePrefix = "swa_bridge_";

// The UAV index of a participant named <prefix><I> (I in decimal as std::to_string writes it); nullopt otherwise.
inline std::optional<int> indexAfter(const std::string& participant_name, const std::string& prefix) {
  if (participant_name.rfind(prefix, 0) != 0) return std::nullopt;
  const std::string digits = participant_name.substr(prefix.size());
  if (digits.empty() || digits.size() > 6 || (digits.size() > 1 && digits[0] == '0')) return std::nullopt;
  if (!std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; })) return std::nullopt;
  return std::stoi(digits);
}

// The UAV index of a participant named swa_agent_<I>, or of a bridge named swa_bridge_<I>.
inline std::optional<int> agentIndex(const std::string& name) { return indexAfter(name, kAgentNamePrefix); }
inline std::optional<int> bridgeIndex(const std::string& name) { return indexAfter(name, kBridgeNamePrefix); }

namespace detail {

inline std::string who(const Endpoint& e) {
  return (e.participant.empty() ? std::string("<unnamed>") : e.participant) + " [" + e.participant_guid + "]";
}

inline bool startsWith(const std::string& s, const std::string& prefix) { return s.rfind(prefix, 0) == 0; }

}  // namespace detail

// Every breach of the isolation rules, one readable line each; empty when the endpoints are clean:
//  - an endpoint whose participant never announced a name (it could be an agent: it cannot be cleared);
//  - a participant whose name starts with swa_agent_ but is not swa_agent_<I> (an agent that cannot be placed);
//  - an agent reading swa/truth (ground truth is for the monitor only);
//  - an agent reading anything outside swa/uav<I>/ other than swa/clock and swa/swarm/mission, or writing anything
//    outside swa/uav<I>/ (the mission too: only the ground writes it);
//  - an agent reading a topic that another agent participant writes.
inline std::vector<std::string> auditIsolation(const std::vector<Endpoint>& endpoints) {
  std::vector<std::string> violations;
  std::set<std::string> unnamed;
  for (const Endpoint& e : endpoints) {
    if (e.participant.empty() && unnamed.insert(e.participant_guid).second) {
      violations.push_back("participant [" + e.participant_guid + "] has endpoints but never announced its name");
    }
  }
  std::set<std::string> misnamed;
  for (const Endpoint& e : endpoints) {
    if (detail::startsWith(e.participant, kAgentNamePrefix) && !agentIndex(e.participant) &&
        misnamed.insert(e.participant_guid).second) {
      violations.push_back(detail::who(e) + " is named like an agent but not swa_agent_<I>");
    }
  }
  for (const Endpoint& e : endpoints) {
    const std::optional<int> id = agentIndex(e.participant);
    if (!id) continue;
    const std::string own = dds::topics::uavPrefix(*id);
    if (e.kind == EndpointKind::kWriter) {
      if (!detail::startsWith(e.topic, own)) {
        violations.push_back(detail::who(e) + " writes " + e.topic + ", outside its own namespace " + own);
      }
      continue;
    }
    if (e.topic == dds::topics::kTruth) {
      violations.push_back(detail::who(e) + " reads " + e.topic + ": ground truth is for the monitor only");
    } else if (e.topic != dds::topics::kClock && e.topic != dds::topics::kMission &&
               !detail::startsWith(e.topic, own)) {
      violations.push_back(detail::who(e) + " reads " + e.topic + ", outside its own namespace " + own +
                           ", the clock and the ground's mission");
    }
    for (const Endpoint& w : endpoints) {
      if (w.kind == EndpointKind::kWriter && w.topic == e.topic && agentIndex(w.participant) &&
          w.participant_guid != e.participant_guid) {
        violations.push_back(detail::who(e) + " reads " + e.topic + ", which agent " + detail::who(w) + " writes");
      }
    }
  }
  return violations;
}

// Completeness, so that the isolation audit cannot pass on too little: each agent 0..agent_count-1 is exactly one
// participant, and it has exactly one reader on each of swa/uav<I>/{imu,detections,gnss} (one on swa/uav<I>/sensors
// and one on swa/clock allowed; one on swa/swarm/mission required), exactly one writer on each of
// swa/uav<I>/{cmd_vel,state} (one on cmd_vel_stamped allowed), and nothing else. Agents with an index outside
// 0..agent_count-1 are reported too.
inline std::vector<std::string> auditAgentEndpoints(const std::vector<Endpoint>& endpoints, int agent_count) {
  using Key = std::pair<EndpointKind, std::string>;
  std::map<int, std::map<std::string, std::map<Key, int>>> seen;  // agent -> participant guid -> endpoint -> count
  for (const Endpoint& e : endpoints) {
    if (const std::optional<int> id = agentIndex(e.participant)) ++seen[*id][e.participant_guid][{e.kind, e.topic}];
  }
  std::vector<std::string> problems;
  for (const auto& [id, participants] : seen) {
    if (id >= agent_count) {
      problems.push_back(kAgentNamePrefix + std::to_string(id) + " is not one of the " + std::to_string(agent_count) +
                         " agents of this run");
    }
  }
  const auto kindName = [](EndpointKind k) { return k == EndpointKind::kReader ? "reader" : "writer"; };
  for (int id = 0; id < agent_count; ++id) {
    const std::string name = kAgentNamePrefix + std::to_string(id);
    const auto it = seen.find(id);
    if (it == seen.end()) {
      problems.push_back(name + " was never discovered with any endpoint");
      continue;
    }
    if (it->second.size() != 1) {
      problems.push_back(std::to_string(it->second.size()) + " participants are named " + name);
      continue;
    }
    const std::map<Key, int>& have = it->second.begin()->second;
    const std::map<Key, bool> expected = {
        // endpoint -> required
        {{EndpointKind::kReader, dds::topics::imu(id)}, true},
        {{EndpointKind::kReader, dds::topics::detections(id)}, true},
        {{EndpointKind::kReader, dds::topics::gnss(id)}, true},
        {{EndpointKind::kReader, dds::topics::sensors(id)}, false},  // the simulator's frames, SWA naming
        {{EndpointKind::kReader, dds::topics::kClock}, false},
        {{EndpointKind::kReader, dds::topics::kMission}, true},  // the ground's (issue #45)
        {{EndpointKind::kWriter, dds::topics::cmdVel(id)}, true},
        {{EndpointKind::kWriter, dds::topics::cmdVelStamped(id)}, false},  // the ros2 naming
        {{EndpointKind::kWriter, dds::topics::state(id)}, true}};
    for (const auto& [key, required] : expected) {
      const auto h = have.find(key);
      const int count = h == have.end() ? 0 : h->second;
      if (count == 0 && required) problems.push_back(name + " has no " + kindName(key.first) + " on " + key.second);
      if (count > 1) {
        problems.push_back(name + " has " + std::to_string(count) + " " + kindName(key.first) + "s on " + key.second);
      }
    }
    for (const auto& [key, count] : have) {
      if (expected.count(key) == 0) {
        problems.push_back(name + " has an unexpected " + kindName(key.first) + " on " + key.second);
      }
    }
  }
  return problems;
}

// What an autopilot's topics look like to the bridge audit: which of them bridge I may read and write, which it must
// have, and which belong to any vehicle (no agent may touch those).
struct VehicleTopics {
  std::string name;                    // "PX4", "ArduPilot"
  std::function<std::string(int)> ns;  // vehicle I's namespace
  std::function<bool(const std::string& ns, EndpointKind, const std::string& topic)> allowed;
  std::function<std::vector<std::pair<EndpointKind, std::string>>(const std::string& ns)> required;
  std::function<bool(const std::string& topic)> anyVehicle;
};

// PX4: bridge I reads rt/<ns_I>/fmu/out/..., writes rt/<ns_I>/fmu/in/...
inline VehicleTopics px4Topics(std::function<std::string(int)> ns) {
  return VehicleTopics{"PX4", std::move(ns),
                       [](const std::string& n, EndpointKind kind, const std::string& topic) {
                         return detail::startsWith(topic, kind == EndpointKind::kReader ? dds::topics::px4Out(n, "")
                                                                                        : dds::topics::px4In(n, ""));
                       },
                       [](const std::string& n) {
                         return std::vector<std::pair<EndpointKind, std::string>>{
                             {EndpointKind::kReader, dds::topics::px4Out(n, "vehicle_attitude")},
                             {EndpointKind::kWriter, dds::topics::px4In(n, "trajectory_setpoint")},
                             {EndpointKind::kWriter, dds::topics::px4In(n, "offboard_control_mode")}};
                       },
                       [](const std::string& topic) {
                         return detail::startsWith(topic, "rt/") && topic.find("/fmu/") != std::string::npos;
                       }};
}

// ArduPilot: bridge I reads rt/<ns_I>/... but cmd_vel and tf, and its services' replies rr/<ns_I>/..., writes
// rt/<ns_I>/cmd_vel, rt/<ns_I>/tf (the external odometry) and the requests rq/<ns_I>/...
inline VehicleTopics ardupilotTopics(std::function<std::string(int)> ns) {
  return VehicleTopics{"ArduPilot", std::move(ns),
                       [](const std::string& n, EndpointKind kind, const std::string& topic) {
                         const std::string cmd_vel = dds::topics::apTopic(n, "cmd_vel");
                         const std::string tf = dds::topics::apTopic(n, "tf");
                         if (kind == EndpointKind::kWriter) {
                           return topic == cmd_vel || topic == tf || detail::startsWith(topic, "rq/" + n + "/");
                         }
                         return (detail::startsWith(topic, "rt/" + n + "/") && topic != cmd_vel && topic != tf) ||
                                detail::startsWith(topic, "rr/" + n + "/");
                       },
                       [](const std::string& n) {
                         return std::vector<std::pair<EndpointKind, std::string>>{
                             {EndpointKind::kReader, dds::topics::apTopic(n, "imu/experimental/data")},
                             {EndpointKind::kReader, dds::topics::apTopic(n, "status")},
                             {EndpointKind::kWriter, dds::topics::apTopic(n, "cmd_vel")}};
                       },
                       [](const std::string& topic) {
                         return detail::startsWith(topic, "rt/ap/") || detail::startsWith(topic, "rq/ap/") ||
                                detail::startsWith(topic, "rr/ap/");
                       }};
}

// The autopilot bridges (swa_px4_bridge, participants swa_bridge_<I>) of a run through an autopilot: bridge I reads
// only its vehicle's topics (`vehicle`) and swa/uav<I>/{cmd_vel,state}, writes only its vehicle's and swa/uav<I>/{imu,
// bridge_state}; exactly one participant per bridge 0..bridge_count-1; and no agent reads or writes any vehicle's
// topic. Every breach and every gap, one line each.
inline std::vector<std::string> auditBridges(const std::vector<Endpoint>& endpoints, int bridge_count,
                                             const VehicleTopics& vehicle) {
  std::vector<std::string> problems;
  std::map<int, std::set<std::string>> guids;
  std::map<int, std::set<std::pair<EndpointKind, std::string>>> seen;
  for (const Endpoint& e : endpoints) {
    if (agentIndex(e.participant) && vehicle.anyVehicle(e.topic)) {
      problems.push_back(detail::who(e) + " touches " + vehicle.name + "'s " + e.topic + ": only its bridge may");
    }
    if (detail::startsWith(e.participant, kBridgeNamePrefix) && !bridgeIndex(e.participant)) {
      problems.push_back(detail::who(e) + " is named like a bridge but not swa_bridge_<I>");
    }
    const std::optional<int> id = bridgeIndex(e.participant);
    if (!id) continue;
    guids[*id].insert(e.participant_guid);
    seen[*id].insert({e.kind, e.topic});
    // its own agent's commands and state (the estimate it feeds its vehicle as external odometry, issue #43)
    const bool own_uav = e.kind == EndpointKind::kReader
                             ? e.topic == dds::topics::cmdVel(*id) || e.topic == dds::topics::state(*id)
                             : e.topic == dds::topics::imu(*id) || e.topic == dds::topics::bridgeState(*id);
    if (!own_uav && !vehicle.allowed(vehicle.ns(*id), e.kind, e.topic)) {
      problems.push_back(detail::who(e) + (e.kind == EndpointKind::kReader ? " reads " : " writes ") + e.topic +
                         ", which is not its vehicle's (" + vehicle.ns(*id) + ") nor UAV " + std::to_string(*id) +
                         "'s");
    }
  }
  for (int id = 0; id < bridge_count; ++id) {
    const std::string name = kBridgeNamePrefix + std::to_string(id);
    if (guids[id].size() != 1) {
      problems.push_back(std::to_string(guids[id].size()) + " participants are named " + name);
      continue;
    }
    std::vector<std::pair<EndpointKind, std::string>> required = vehicle.required(vehicle.ns(id));
    required.emplace_back(EndpointKind::kReader, dds::topics::cmdVel(id));
    required.emplace_back(EndpointKind::kWriter, dds::topics::imu(id));
    for (const auto& [kind, topic] : required) {
      if (seen[id].count({kind, topic}) == 0) {
        problems.push_back(name + " has no " + (kind == EndpointKind::kReader ? "reader" : "writer") + " on " + topic);
      }
    }
  }
  for (const auto& [id, g] : guids) {
    if (id >= bridge_count) problems.push_back(kBridgeNamePrefix + std::to_string(id) + " is not a bridge of this run");
  }
  return problems;
}

// The endpoints as a table sorted by participant, kind and topic, one line each.
inline std::string endpointTable(std::vector<Endpoint> endpoints) {
  std::sort(endpoints.begin(), endpoints.end(), [](const Endpoint& a, const Endpoint& b) {
    return std::tie(a.participant, a.participant_guid, a.kind, a.topic, a.type) <
           std::tie(b.participant, b.participant_guid, b.kind, b.topic, b.type);
  });
  std::ostringstream out;
  for (const Endpoint& e : endpoints) {
    out << "  " << detail::who(e) << "  " << (e.kind == EndpointKind::kReader ? "reads " : "writes") << "  " << e.topic
        << "  (" << e.type << ")\n";
  }
  return out.str();
}

}  // namespace swa::testing

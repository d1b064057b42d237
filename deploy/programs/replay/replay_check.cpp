#include "replay_check.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include <swa/msg/DetectionsPubSubTypes.h>
#include <swa/msg/GnssFixPubSubTypes.h>
#include <swa/msg/ImuPubSubTypes.h>
#include <swa/msg/VelocitySetpointPubSubTypes.h>

#include "swa/agent/agent.h"
#include "swa/dds/raw_type.h"
#include "swa/wire/agent_feed.h"
#include "swa/wire/samples.h"

namespace swa::replay {
namespace {

UavCheck checkUav(int uav, const UavRecording& recording, const agent::AgentConfig& config) {
  UavCheck c;
  c.uav = uav;
  const auto self = static_cast<std::uint32_t>(uav);

  // The recorded commands by stamp: swa_agent stamps a command with the IMU sample it answers.
  std::map<std::int64_t, const Payload*> recorded;
  for (const Payload& p : recording.commands) {
    msg::VelocitySetpoint m;
    if (!dds::decodePayload<msg::VelocitySetpointPubSubType>(p, m)) continue;
    ++c.recorded;
    recorded.emplace(m.header().stamp_ns(), &p);
  }
  std::map<std::int64_t, bool> answered;

  agent::Agent core(config);
  wire::AgentFeed feed(core, self);  // as swa_agent feeds its agent (agent/node/agent_samples.cpp)
  for (const InputSample& in : recording.inputs) {
    ++c.inputs;
    if (in.input == Input::kImu) {
      msg::Imu imu;
      if (!dds::decodePayload<msg::ImuPubSubType>(in.payload, imu) || !feed.isFor(imu.uav_id())) {
        ++c.undecodable;
        continue;
      }
      const std::optional<msg::VelocitySetpoint> answer = feed.onImu(imu);
      if (!answer) continue;  // a rejected sample is not answered
      const msg::VelocitySetpoint& out = *answer;
      ++c.replayed;
      const auto it = recorded.find(out.header().stamp_ns());
      if (it == recorded.end()) {
        ++c.not_recorded;
        if (!c.first_not_recorded_ns) c.first_not_recorded_ns = out.header().stamp_ns();
        continue;
      }
      answered[it->first] = true;
      if (dds::encodePayload<msg::VelocitySetpointPubSubType>(out) == *it->second) {
        ++c.identical;
        continue;
      }
      ++c.differing;
      msg::VelocitySetpoint was;
      dds::decodePayload<msg::VelocitySetpointPubSubType>(*it->second, was);
      c.max_speed_difference_mps =
          std::max(c.max_speed_difference_mps, std::hypot(out.vx_mps() - was.vx_mps(), out.vy_mps() - was.vy_mps()));
      c.max_yaw_rate_difference_radps =
          std::max(c.max_yaw_rate_difference_radps, std::abs(out.yaw_rate_radps() - was.yaw_rate_radps()));
      if (!c.first_difference) {
        c.first_difference = CommandDifference{it->first,    was.vx_mps(), was.vy_mps(),        was.yaw_rate_radps(),
                                               out.vx_mps(), out.vy_mps(), out.yaw_rate_radps()};
      }
    } else if (in.input == Input::kDetections) {
      msg::Detections det;
      if (!dds::decodePayload<msg::DetectionsPubSubType>(in.payload, det) || !feed.onDetections(det)) {
        ++c.undecodable;
        continue;
      }
    } else {
      msg::GnssFix gnss;
      if (!dds::decodePayload<msg::GnssFixPubSubType>(in.payload, gnss) || !feed.onGnss(gnss)) {
        ++c.undecodable;
        continue;
      }
    }
  }
  c.not_replayed = c.recorded - std::min<std::uint64_t>(c.recorded, answered.size());
  return c;
}

}  // namespace

std::vector<UavCheck> checkRun(const RecordedRun& run, const agent::AgentConfig& config) {
  std::vector<UavCheck> checks;
  for (const auto& [uav, recording] : run.uavs) checks.push_back(checkUav(uav, recording, config));
  return checks;
}

std::string formatChecks(const std::vector<UavCheck>& checks) {
  std::string out;
  char line[512];
  bool all = !checks.empty();
  bool any_difference = false;
  std::uint64_t not_recorded = 0;
  for (const UavCheck& c : checks) {
    std::snprintf(line, sizeof line,
                  "uav %d: %llu inputs, %llu commands replayed, %llu recorded: %llu identical, %llu differ (largest "
                  "%.3g m/s, %.3g rad/s), %llu not recorded, %llu not replayed%s\n",
                  c.uav, static_cast<unsigned long long>(c.inputs), static_cast<unsigned long long>(c.replayed),
                  static_cast<unsigned long long>(c.recorded), static_cast<unsigned long long>(c.identical),
                  static_cast<unsigned long long>(c.differing), c.max_speed_difference_mps,
                  c.max_yaw_rate_difference_radps, static_cast<unsigned long long>(c.not_recorded),
                  static_cast<unsigned long long>(c.not_replayed),
                  c.undecodable > 0 ? (", " + std::to_string(c.undecodable) + " inputs skipped").c_str() : "");
    out += line;
    if (c.first_difference) {
      const CommandDifference& d = *c.first_difference;
      std::snprintf(line, sizeof line,
                    "  first difference at %.3f s: recorded (%.17g, %.17g) m/s %.17g rad/s, replayed (%.17g, %.17g) "
                    "m/s %.17g rad/s\n",
                    static_cast<double>(d.stamp_ns) * 1e-9, d.recorded_vx, d.recorded_vy, d.recorded_yaw_rate,
                    d.replayed_vx, d.replayed_vy, d.replayed_yaw_rate);
      out += line;
    }
    if (c.first_not_recorded_ns) {
      std::snprintf(line, sizeof line, "  first command missing from the recording at %.3f s\n",
                    static_cast<double>(*c.first_not_recorded_ns) * 1e-9);
      out += line;
    }
    all = all && c.identicalRun();
    any_difference = any_difference || c.differing > 0 || c.not_replayed > 0 || c.replayed == 0;
    not_recorded += c.not_recorded;
  }
  if (all) {
    out += "IDENTICAL: every command replayed bit for bit\n";
  } else if (!any_difference && !checks.empty()) {
    // Nothing differs: the recording lacks commands. In a realtime run the monitor can miss one on a loaded host (the
    // command writer keeps only its newest sample, idl/runtime/dds/profiles.xml); a lockstep run waits for it.
    std::snprintf(line, sizeof line,
                  "INCOMPLETE RECORDING: every recorded command replayed bit for bit, but %llu replayed command(s) are "
                  "not in the recording (a realtime recording on a loaded host can miss some; a lockstep one does "
                  "not)\n",
                  static_cast<unsigned long long>(not_recorded));
    out += line;
  } else {
    out += "DIFFERENT: see the lines above\n";
  }
  return out;
}

}  // namespace swa::replay

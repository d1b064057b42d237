#include "recorded_run.h"

#include <algorithm>
#include <tuple>

#include <swa/msg/ImuPubSubTypes.h>

#include "swa/dds/raw_type.h"
#include "swa/recording/mcap_reader.h"
#include "swa/recording/record_set.h"
#include "swa/recording/recording.h"

namespace swa::replay {
namespace {

// A message set 4 Imu on the wire: 4 bytes of encapsulation, the header's 12, uav_id's 4 and three doubles.
constexpr std::size_t kImuSet4Bytes = 44;

}  // namespace

std::optional<std::string> swaTopicOf(const std::string& recorded_topic) {
  if (recorded_topic.rfind("/swa/", 0) == 0) return recorded_topic.substr(1);
  const std::size_t at = recorded_topic.find("/swa/");
  if (at == std::string::npos) return std::nullopt;
  return recorded_topic.substr(at + 1);
}

std::optional<std::pair<int, std::string>> uavTopic(const std::string& swa_topic) {
  const std::string prefix = "swa/uav";
  if (swa_topic.rfind(prefix, 0) != 0) return std::nullopt;
  const std::size_t slash = swa_topic.find('/', prefix.size());
  if (slash == std::string::npos || slash == prefix.size() || slash - prefix.size() > 6) return std::nullopt;
  const std::string digits = swa_topic.substr(prefix.size(), slash - prefix.size());
  if (!std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; })) return std::nullopt;
  return std::make_pair(std::stoi(digits), swa_topic.substr(slash + 1));
}

RecordedRun readRecordedRun(const std::string& path, std::optional<int> only_uav, bool world) {
  recording::McapReader reader(path);
  RecordedRun run;
  run.profile = reader.profile();
  std::uint64_t order = 0;
  while (std::optional<recording::McapReader::Message> m = reader.next()) {
    ++order;
    const std::optional<std::string> topic = swaTopicOf(reader.channels().at(m->channel_id).topic);
    const auto per_uav = topic ? uavTopic(*topic) : std::nullopt;
    if (per_uav) {
      const auto& [uav, leaf] = *per_uav;
      if (only_uav && uav != *only_uav) continue;
      const std::optional<Input> input = leaf == "imu"          ? std::optional<Input>(Input::kImu)
                                         : leaf == "detections" ? std::optional<Input>(Input::kDetections)
                                         : leaf == "gnss"       ? std::optional<Input>(Input::kGnss)
                                                                : std::nullopt;
      if (input) {
        const std::optional<recording::PayloadStamp> stamp = recording::payloadStamp(m->data.data(), m->data.size());
        if (!stamp) {
          ++run.unstamped;
          continue;
        }
        // A recording of message set 4 has shorter IMU samples than today's agents read (set 5 appended the
        // accelerometer): read as set 5 without one, so that old recordings still replay.
        if (*input == Input::kImu) m->data = dds::upgradeAppended<msg::ImuPubSubType>(m->data, kImuSet4Bytes);
        run.uavs[uav].inputs.push_back({static_cast<std::int64_t>(stamp->stamp_ns), *input, order, std::move(m->data)});
      } else if (leaf == "cmd_vel") {
        run.uavs[uav].commands.push_back(std::move(m->data));
      } else {
        ++run.other_topics;
      }
    } else if (world && topic && (*topic == "swa/truth" || *topic == "swa/events" || *topic == "swa/clock")) {
      run.world.push_back({*topic, m->log_time_ns, order, std::move(m->data)});
    } else {
      ++run.other_topics;
    }
  }
  run.truncated = reader.truncated();
  const auto scenario = reader.metadata().find(recording::kScenarioMetadata);
  if (scenario != reader.metadata().end()) {
    const auto yaml = scenario->second.find(recording::kScenarioYamlKey);
    if (yaml != scenario->second.end()) run.scenario_yaml = yaml->second;
  }
  const auto set = reader.metadata().find(recording::kRecordingMetadata);
  if (set != reader.metadata().end()) {
    const auto name = set->second.find(recording::kRecordSetKey);
    if (name != set->second.end()) run.record_set = name->second;
  }
  for (auto& [uav, recording] : run.uavs) {
    std::sort(recording.inputs.begin(), recording.inputs.end(), [](const InputSample& a, const InputSample& b) {
      return std::tie(a.stamp_ns, a.input, a.order) < std::tie(b.stamp_ns, b.input, b.order);
    });
  }
  std::sort(run.world.begin(), run.world.end(), [](const WorldSample& a, const WorldSample& b) {
    return std::tie(a.log_time_ns, a.order) < std::tie(b.log_time_ns, b.order);
  });
  return run;
}

}  // namespace swa::replay

#pragma once
// What swa_replay takes from a recording (swa_monitor --record, an MCAP file): per UAV the agent's inputs (imu,
// detections, gnss payloads) and the commands it sent, the world's topics (truth, events, clock), and the scenario
// the run was flown with. Payloads stay the recorded bytes. No DDS entity.
//
// Memory: every payload of the UAVs asked for (a 30 s, 4-UAV run is about 3 MB); the recording is read once.

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace swa::replay {

using Payload = std::vector<std::uint8_t>;

// The agent's three inputs, in the order the agent processes samples of equal stamp (agent/node/sample_order.h).
enum class Input : int { kImu = 0, kDetections = 1, kGnss = 2 };

struct InputSample {
  std::int64_t stamp_ns = 0;  // MessageHeader.stamp_ns
  Input input = Input::kImu;
  std::uint64_t order = 0;  // position in the file (ties)
  Payload payload;
};

struct UavRecording {
  std::vector<InputSample> inputs;  // sorted by (stamp, input, order): the agent's processing order in lockstep
  std::vector<Payload> commands;    // cmd_vel payloads, in file order
};

// A message of a world topic, kept for re-publishing.
struct WorldSample {
  std::string topic;  // SWA name: swa/truth, swa/events, swa/clock
  std::uint64_t log_time_ns = 0;
  std::uint64_t order = 0;
  Payload payload;
};

struct RecordedRun {
  std::map<int, UavRecording> uavs;
  std::vector<WorldSample> world;            // by (log time, order)
  std::optional<std::string> scenario_yaml;  // the run's effective scenario, if the recorder knew it
  std::optional<std::string> record_set;     // which topics the recorder took (swa/recording/record_set.h), if it said
  std::string profile;
  bool truncated = false;          // the file ends before its Data End (a recorder that crashed)
  std::uint64_t unstamped = 0;     // input payloads without a readable header: skipped
  std::uint64_t other_topics = 0;  // messages of topics swa_replay does not use (states, metrics, ...)
};

// The SWA topic a recorded topic stands for: "/swa/uav3/imu" or "/team/swa/uav3/imu" (ros2 naming with a namespace)
// -> "swa/uav3/imu"; nullopt if the topic is not one of SWA's.
std::optional<std::string> swaTopicOf(const std::string& recorded_topic);
// UAV and leaf of a per-UAV SWA topic: "swa/uav3/imu" -> (3, "imu").
std::optional<std::pair<int, std::string>> uavTopic(const std::string& swa_topic);

// Reads `path` (McapReader: throws recording::McapError on a file that is not MCAP or is malformed). `only_uav`: keep
// the inputs and commands of that UAV only; `world`: keep the world topics.
RecordedRun readRecordedRun(const std::string& path, std::optional<int> only_uav, bool world);

}  // namespace swa::replay

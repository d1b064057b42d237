#pragma once
// Which topics a recording holds (swa_monitor --record-set, swa_launch --record=SET). A complete recording has to
// receive every UAV's sensors and commands, which costs the monitor as much as a reader of all of them
// (BENCHMARKS.md, issue #24); the monitor's own inputs are a small fraction of that traffic.
//
// The set is stored in the file as metadata kRecordingMetadata {kRecordSetKey: name}, so a reader that needs the
// sensors (swa_replay) can say why a file lacks them instead of finding nothing to replay.

#include <optional>
#include <string>
#include <vector>

namespace swa::recording {

enum class RecordSet {
  kAll,      // every topic of the run: truth, events, clock, and per UAV detections, imu, gnss, cmd_vel, state,
             // bridge_state; plus the monitor's metrics. What swa_replay needs.
  kMonitor,  // what the monitor reads anyway: truth, events, the agents' states, plus its metrics
};

constexpr const char* kRecordingMetadata = "swa_recording";
constexpr const char* kRecordSetKey = "record_set";

// The names on the command line and in the file, in the order --help lists them; the first is the default.
inline std::vector<std::string> recordSetNames() { return {"all", "monitor"}; }

inline std::string toString(RecordSet set) { return set == RecordSet::kMonitor ? "monitor" : "all"; }

inline std::optional<RecordSet> recordSetFromName(const std::string& name) {
  if (name == "all") return RecordSet::kAll;
  if (name == "monitor") return RecordSet::kMonitor;
  return std::nullopt;
}

}  // namespace swa::recording

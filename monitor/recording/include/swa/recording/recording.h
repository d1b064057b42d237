#pragma once
// A run recorded into one MCAP file (mcap_writer.h) as it happens: the DDS payloads of SWA's topics unchanged, each
// channel with its swa_msgs definition (schema encoding ros2msg, message encoding cdr), and the monitor's own channels
// as JSON with a JSON Schema. Thread-safe: DDS listener threads and the monitor's worker write concurrently.
//
// Times: a message's log time is its own MessageHeader.stamp_ns (every swa_msgs message starts with the header): the
// simulation's clock in a simulated run, the drone's monotonic clock on a drone. Viewers then play a lockstep run at
// simulated speed, and swa_replay re-sends it in stamp order. Its publish time is when its writer sent it (DDS source
// timestamp, wall clock). The MCAP sequence is MessageHeader.seq (a gap is a sample lost before the recorder).
//
// The monitor also stores the run's effective scenario as metadata kScenarioMetadata {"scenario.yaml": YAML}, so a
// recording carries the parameters it was flown with (swa_replay --check re-runs the agents with them).

#include <array>
#include <chrono>
#include <cstdint>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "swa/recording/mcap_writer.h"

namespace swa::recording {

// The log time and sequence of a CDR payload of a swa_msgs message (encapsulation header, then MessageHeader);
// nullopt if the payload is too short, not CDR, or its stamp is negative.
struct PayloadStamp {
  std::uint64_t stamp_ns;
  std::uint32_t seq;
};
constexpr const char* kScenarioMetadata = "swa_scenario";
constexpr const char* kScenarioYamlKey = "scenario.yaml";

std::optional<PayloadStamp> payloadStamp(const std::uint8_t* data, std::size_t size);

class Recording {
 public:
  struct Options {
    std::size_t chunk_bytes = 256 * 1024;
    // A chunk is also closed once it is this old (tick()), so a crash loses at most about this much of the run.
    double chunk_max_age_s = 1.0;
  };

  // Creates `path` (MCAP, profile ros2). Throws McapError.
  Recording(const std::string& path, const Options& options);

  // The channel of `topic` ("/swa/uav0/imu") carrying swa_msgs `type` ("Imu"), created on first call. Throws
  // McapError if swa_msgs has no such type.
  std::uint16_t cdrChannel(const std::string& topic, const std::string& type);
  // A JSON channel on `topic` whose messages follow the JSON Schema `schema_json`, named `schema_name`.
  std::uint16_t jsonChannel(const std::string& topic, const std::string& schema_name, const std::string& schema_json);

  // A Metadata record (McapWriter::writeMetadata).
  void writeMetadata(const std::string& name, const std::map<std::string, std::string>& entries);

  // A payload of a cdrChannel. One without a readable stamp is written with its publish time as log time and
  // counted (unstamped()).
  void writeCdr(std::uint16_t channel, const std::vector<std::uint8_t>& payload, std::int64_t publish_time_ns);
  void writeJson(std::uint16_t channel, const std::string& json, std::uint64_t log_time_ns,
                 std::int64_t publish_time_ns);

  // Closes the open chunk if it is older than Options::chunk_max_age_s (call about once a second).
  void tick(std::chrono::steady_clock::time_point now);
  // Finishes the file (summary, footer). Throws McapError; later writes are dropped.
  void close();

  // Whether sample `seq` of writer `writer`, taken by the recording's reader `reader` (a channel it writes to names
  // it), is new to the recording. A reader created again (the monitor re-created its participant) is sent its
  // writers' history once more, most of it recorded already. A writer's samples come in sequence order (reliable; a
  // best-effort reader drops the late ones), so one not past the newest taken from that writer is a repeat: false,
  // and counted (repeats()).
  using WriterId = std::array<std::uint8_t, 16>;
  bool firstDelivery(std::uint16_t reader, const WriterId& writer, std::int64_t seq);

  struct ChannelCount {
    std::string topic, schema, message_encoding;
    std::uint64_t messages = 0;
  };
  std::vector<ChannelCount> channelCounts() const;
  std::uint64_t unstamped() const;
  std::uint64_t repeats() const;
  const std::string& path() const { return path_; }

 private:
  void written(std::chrono::steady_clock::time_point now);  // under mutex_

  const std::string path_;
  const Options options_;
  mutable std::mutex mutex_;
  McapWriter writer_;
  std::map<std::string, std::uint16_t> schema_ids_;   // by schema name
  std::map<std::string, std::uint16_t> channel_ids_;  // by topic
  std::vector<ChannelCount> channels_;                // by channel id
  std::uint64_t unstamped_ = 0;
  std::map<std::pair<std::uint16_t, WriterId>, std::int64_t> newest_seq_;  // by reader and writer
  std::uint64_t repeats_ = 0;
  std::optional<std::chrono::steady_clock::time_point> chunk_opened_;
  bool closed_ = false;
};

// recording.json: the file, its profile, the payloads without a stamp, the repeats not recorded again, and per channel
// its schema, encodings and how many messages were written (the monitor's own count, which a reader of the file must
// find again: tests/record/mcap_reader). Throws
// std::runtime_error if `path` cannot be written.
void writeRecordingManifest(const std::string& path, const Recording& recording);

}  // namespace swa::recording

#include "swa/recording/recording.h"

#include <algorithm>

#include <fstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "swa/msg_defs/ros_definition.h"

namespace swa::recording {
namespace {

std::uint64_t littleEndian(const std::uint8_t* p, int n) {
  std::uint64_t v = 0;
  for (int i = n - 1; i >= 0; --i) v = (v << 8) | p[i];
  return v;
}
std::uint64_t bigEndian(const std::uint8_t* p, int n) {
  std::uint64_t v = 0;
  for (int i = 0; i < n; ++i) v = (v << 8) | p[i];
  return v;
}

}  // namespace

std::optional<PayloadStamp> payloadStamp(const std::uint8_t* data, std::size_t size) {
  // Encapsulation: 0x00 0x00 CDR big endian, 0x00 0x01 CDR little endian (XCDR1, what SWA writes), then two option
  // bytes. MessageHeader is the body's first member: int64 stamp_ns at body offset 0, uint32 seq at 8.
  constexpr std::size_t kBody = 4;
  if (size < kBody + 12 || data[0] != 0x00 || data[1] > 0x01) return std::nullopt;
  const bool little = data[1] == 0x01;
  const std::uint64_t stamp = little ? littleEndian(data + kBody, 8) : bigEndian(data + kBody, 8);
  const auto seq =
      static_cast<std::uint32_t>(little ? littleEndian(data + kBody + 8, 4) : bigEndian(data + kBody + 8, 4));
  if (static_cast<std::int64_t>(stamp) < 0) return std::nullopt;
  return PayloadStamp{stamp, seq};
}

Recording::Recording(const std::string& path, const Options& options)
    : path_(path), options_(options), writer_(path, McapWriter::Options{"ros2", "swa", options.chunk_bytes}) {}

std::uint16_t Recording::cdrChannel(const std::string& topic, const std::string& type) {
  const std::lock_guard<std::mutex> lock(mutex_);
  if (auto it = channel_ids_.find(topic); it != channel_ids_.end()) return it->second;
  const std::string schema = msg_defs::rosTypeName(type);
  auto schema_it = schema_ids_.find(schema);
  if (schema_it == schema_ids_.end()) {
    const std::optional<std::string> definition = msg_defs::rosDefinition(type);
    if (!definition) throw McapError(std::string("no message ") + type + " in " + msg_defs::kPackage);
    schema_it = schema_ids_.emplace(schema, writer_.addSchema(schema, "ros2msg", *definition)).first;
  }
  const std::uint16_t id = writer_.addChannel(schema_it->second, topic, "cdr");
  channel_ids_.emplace(topic, id);
  channels_.push_back({topic, schema, "cdr", 0});
  return id;
}

std::uint16_t Recording::jsonChannel(const std::string& topic, const std::string& schema_name,
                                     const std::string& schema_json) {
  const std::lock_guard<std::mutex> lock(mutex_);
  if (auto it = channel_ids_.find(topic); it != channel_ids_.end()) return it->second;
  auto schema_it = schema_ids_.find(schema_name);
  if (schema_it == schema_ids_.end()) {
    schema_it = schema_ids_.emplace(schema_name, writer_.addSchema(schema_name, "jsonschema", schema_json)).first;
  }
  const std::uint16_t id = writer_.addChannel(schema_it->second, topic, "json");
  channel_ids_.emplace(topic, id);
  channels_.push_back({topic, schema_name, "json", 0});
  return id;
}

void Recording::writeMetadata(const std::string& name, const std::map<std::string, std::string>& entries) {
  const std::lock_guard<std::mutex> lock(mutex_);
  if (closed_) return;
  writer_.writeMetadata(name, entries);
  chunk_opened_.reset();
}

void Recording::writeCdr(std::uint16_t channel, const std::vector<std::uint8_t>& payload,
                         std::int64_t publish_time_ns) {
  const auto publish = static_cast<std::uint64_t>(std::max<std::int64_t>(publish_time_ns, 0));
  const std::optional<PayloadStamp> stamp = payloadStamp(payload.data(), payload.size());
  const std::lock_guard<std::mutex> lock(mutex_);
  if (closed_) return;
  if (!stamp) ++unstamped_;
  writer_.write(channel, stamp ? stamp->seq : 0, stamp ? stamp->stamp_ns : publish, publish, payload.data(),
                payload.size());
  ++channels_.at(channel).messages;
  written(std::chrono::steady_clock::now());
}

void Recording::writeJson(std::uint16_t channel, const std::string& json, std::uint64_t log_time_ns,
                          std::int64_t publish_time_ns) {
  const std::lock_guard<std::mutex> lock(mutex_);
  if (closed_) return;
  const auto sequence = static_cast<std::uint32_t>(channels_.at(channel).messages);
  writer_.write(channel, sequence, log_time_ns, static_cast<std::uint64_t>(std::max<std::int64_t>(publish_time_ns, 0)),
                reinterpret_cast<const std::uint8_t*>(json.data()), json.size());
  ++channels_.at(channel).messages;
  written(std::chrono::steady_clock::now());
}

void Recording::written(std::chrono::steady_clock::time_point now) {
  if (!writer_.chunkOpen()) {
    chunk_opened_.reset();  // the write filled and closed the chunk
  } else if (!chunk_opened_) {
    chunk_opened_ = now;
  }
}

void Recording::tick(std::chrono::steady_clock::time_point now) {
  const std::lock_guard<std::mutex> lock(mutex_);
  if (closed_ || !chunk_opened_) return;
  if (std::chrono::duration<double>(now - *chunk_opened_).count() < options_.chunk_max_age_s) return;
  writer_.closeChunk();
  chunk_opened_.reset();
}

void Recording::close() {
  const std::lock_guard<std::mutex> lock(mutex_);
  if (closed_) return;
  closed_ = true;
  writer_.close();
}

std::vector<Recording::ChannelCount> Recording::channelCounts() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return channels_;
}

std::uint64_t Recording::unstamped() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return unstamped_;
}

bool Recording::firstDelivery(std::uint16_t reader, const WriterId& writer, std::int64_t seq) {
  const std::lock_guard<std::mutex> lock(mutex_);
  const auto [it, first] = newest_seq_.try_emplace({reader, writer}, seq);
  if (first || seq > it->second) {
    it->second = seq;
    return true;
  }
  ++repeats_;
  return false;
}

std::uint64_t Recording::repeats() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return repeats_;
}

void writeRecordingManifest(const std::string& path, const Recording& recording) {
  nlohmann::ordered_json channels = nlohmann::ordered_json::object();
  for (const Recording::ChannelCount& c : recording.channelCounts()) {
    channels[c.topic] = {{"schema", c.schema},
                         {"schema_encoding", c.message_encoding == "cdr" ? "ros2msg" : "jsonschema"},
                         {"message_encoding", c.message_encoding},
                         {"messages", c.messages}};
  }
  const nlohmann::ordered_json manifest = {{"file", recording.path()},
                                           {"profile", "ros2"},
                                           {"unstamped", recording.unstamped()},
                                           {"repeats", recording.repeats()},
                                           {"channels", channels}};
  std::ofstream out(path);
  out << manifest.dump(2) << "\n";
  if (!out) throw std::runtime_error("cannot write " + path);
}

}  // namespace swa::recording

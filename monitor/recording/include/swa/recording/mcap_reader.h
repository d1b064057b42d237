#pragma once
// A streaming reader of MCAP files (https://mcap.dev/spec), enough for what SWA records and replays: schemas,
// channels, messages (in chunks or not), metadata, in file order. Uncompressed chunks only (what McapWriter writes);
// a compressed chunk is an error naming its compression. Reads a file cut short by a crash up to its last whole
// record, and says so (truncated()). Memory: one chunk at a time.

#include <cstdint>
#include <fstream>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "swa/recording/mcap_writer.h"

namespace swa::recording {

class McapReader {
 public:
  struct Schema {
    std::uint16_t id = 0;
    std::string name, encoding, data;
  };
  struct Channel {
    std::uint16_t id = 0, schema_id = 0;
    std::string topic, message_encoding;
  };
  struct Message {
    std::uint16_t channel_id = 0;
    std::uint32_t sequence = 0;
    std::uint64_t log_time_ns = 0, publish_time_ns = 0;
    std::vector<std::uint8_t> data;
  };

  // Throws McapError if `path` cannot be read or does not start with the MCAP magic and a Header.
  explicit McapReader(const std::string& path);

  // The next message in file order; nullopt at the end of the data section or of a cut file. Throws McapError on a
  // malformed record (a length that does not fit its record, a compressed chunk, a message on an unknown channel).
  std::optional<Message> next();

  const std::string& profile() const { return profile_; }
  // What the records read so far declared (a channel is known once its record has been read, before its messages).
  const std::map<std::uint16_t, Schema>& schemas() const { return schemas_; }
  const std::map<std::uint16_t, Channel>& channels() const { return channels_; }
  const std::map<std::string, std::map<std::string, std::string>>& metadata() const { return metadata_; }
  // The file ended inside a record or without a Data End (a writer that did not finish).
  bool truncated() const { return truncated_; }

 private:
  // Reads one record of the data section into (opcode, content); false at its end.
  bool nextRecord(std::uint8_t& opcode, std::vector<std::uint8_t>& content);
  // Handles a Schema, Channel or Metadata record; Message records come back through `message`.
  void take(std::uint8_t opcode, const std::vector<std::uint8_t>& content, std::optional<Message>& message);

  std::string path_;
  std::ifstream in_;
  std::string profile_;
  std::map<std::uint16_t, Schema> schemas_;
  std::map<std::uint16_t, Channel> channels_;
  std::map<std::string, std::map<std::string, std::string>> metadata_;
  std::vector<std::uint8_t> chunk_;  // records of the chunk being read
  std::size_t chunk_pos_ = 0;
  bool done_ = false;
  bool truncated_ = false;
};

}  // namespace swa::recording

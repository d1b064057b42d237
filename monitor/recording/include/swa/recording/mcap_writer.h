#pragma once
// A writer of MCAP files (https://mcap.dev/spec, format version 0), the robotics ecosystem's recording format: ROS 2's
// default bag storage, opened by Foxglove, Lichtblick and PlotJuggler. No MCAP library is packaged for Debian 12, so
// the format is written here, whole and nothing more: one self-contained file pair, proven against the reference
// reader (@mcap/core, tests/record/).
//
// Layout: magic, Header, then chunks (uncompressed), each followed by one Message Index per channel it holds; then
// Data End, the summary (every Schema and Channel, Statistics, one Chunk Index per chunk), the Summary Offsets, the
// Footer and the magic again. Viewers seek through the chunk indexes.
//
// Crash safety: a Schema or Channel record goes into the chunk being filled before the first message that needs it,
// so every chunk on disk can be read by a streaming reader without the summary; each closed chunk is handed to the
// kernel at once (fflush). A process killed mid-run leaves a file readable up to its last closed chunk.
//
// Memory: one chunk's records and message indexes (closeChunk() when it reaches Options::chunk_bytes, or when the
// caller decides it is old enough), plus one small Chunk Index per closed chunk for the summary.
//
// Not thread-safe: one owner (swa/recording/recording.h serialises its callers).

#include <cstdint>
#include <cstdio>
#include <map>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace swa::recording {

// CRC-32 (ISO-HDLC, as zlib): `crc` continues a previous call (0 to start).
std::uint32_t crc32(const std::uint8_t* data, std::size_t size, std::uint32_t crc = 0);

class McapError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class McapWriter {
 public:
  struct Options {
    std::string profile = "ros2";          // the Header's profile: what the channels' metadata and encodings follow
    std::string library = "swa";           // the Header's writer library
    std::size_t chunk_bytes = 256 * 1024;  // a chunk is closed once its records reach this size
  };

  // Creates (truncates) `path` and writes the magic and Header. Throws McapError with the reason.
  McapWriter(const std::string& path, const Options& options);
  // Finishes the file (close()) if it was not; errors are swallowed (call close() to see them).
  ~McapWriter();
  McapWriter(const McapWriter&) = delete;
  McapWriter& operator=(const McapWriter&) = delete;

  // A schema: `name` ("swa_msgs/msg/Imu"), `encoding` ("ros2msg", "jsonschema"), its definition. Ids from 1.
  std::uint16_t addSchema(const std::string& name, const std::string& encoding, std::string_view data);
  // A channel on `topic` with messages of `schema_id` (0: none) in `message_encoding` ("cdr", "json"). Ids from 0.
  std::uint16_t addChannel(std::uint16_t schema_id, const std::string& topic, const std::string& message_encoding,
                           const std::map<std::string, std::string>& metadata = {});
  // One message: `log_time_ns` orders it for viewers, `publish_time_ns` is when it was sent. Throws McapError on an
  // unknown channel or a failed write.
  void write(std::uint16_t channel_id, std::uint32_t sequence, std::uint64_t log_time_ns, std::uint64_t publish_time_ns,
             const std::uint8_t* data, std::size_t size);

  // A Metadata record `name` with `entries` (e.g. the run's effective scenario), outside any chunk: the chunk being
  // filled is written first. Indexed in the summary.
  void writeMetadata(const std::string& name, const std::map<std::string, std::string>& entries);

  // Writes the chunk being filled, if any, and hands it to the kernel.
  void closeChunk();
  // The chunk being filled has records (closeChunk() would write something).
  bool chunkOpen() const { return !chunk_.empty(); }
  // Writes the last chunk, the summary and the footer, and closes the file. Idempotent. Throws McapError.
  void close();

  std::uint64_t messageCount() const { return message_count_; }
  std::uint32_t chunkCount() const { return static_cast<std::uint32_t>(chunk_indexes_.size()); }
  std::uint64_t messageCount(std::uint16_t channel_id) const;

 private:
  struct SchemaRecord {
    std::uint16_t id;
    std::string name, encoding, data;
  };
  struct ChannelRecord {
    std::uint16_t id, schema_id;
    std::string topic, message_encoding;
    std::map<std::string, std::string> metadata;
  };
  struct ChunkIndex {
    std::uint64_t start_ns, end_ns, offset, length, index_length, size;
    std::map<std::uint16_t, std::uint64_t> index_offsets;
  };

  void put(const std::vector<std::uint8_t>& bytes);  // to the file, counted in the data section's CRC and offset
  void putFooterAndClose();
  static std::vector<std::uint8_t> schemaRecord(const SchemaRecord& s);
  static std::vector<std::uint8_t> channelRecord(const ChannelRecord& c);

  Options options_;
  std::string path_;
  std::FILE* file_ = nullptr;
  std::uint64_t offset_ = 0;    // bytes written so far
  std::uint32_t data_crc_ = 0;  // of the data section so far
  std::vector<SchemaRecord> schemas_;
  std::vector<ChannelRecord> channels_;
  std::vector<bool> schema_in_chunk_stream_;   // per schema: already in a chunk (a streaming reader knows it)
  std::vector<bool> channel_in_chunk_stream_;  // per channel: the same
  std::vector<std::uint64_t> channel_counts_;
  std::uint64_t message_count_ = 0;
  std::uint64_t start_ns_ = 0, end_ns_ = 0;  // over every message (valid when message_count_ > 0)

  // The chunk being filled.
  std::vector<std::uint8_t> chunk_;
  std::uint64_t chunk_start_ns_ = 0, chunk_end_ns_ = 0;
  bool chunk_has_messages_ = false;
  std::map<std::uint16_t, std::vector<std::pair<std::uint64_t, std::uint64_t>>> chunk_index_;  // (log time, offset)

  std::vector<ChunkIndex> chunk_indexes_;
  struct MetadataIndex {
    std::uint64_t offset, length;
    std::string name;
  };
  std::vector<MetadataIndex> metadata_indexes_;
  bool closed_ = false;
};

}  // namespace swa::recording

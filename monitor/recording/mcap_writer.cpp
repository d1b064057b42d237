#include "swa/recording/mcap_writer.h"

#include <array>
#include <cerrno>
#include <cstring>

#include "mcap_format.h"

namespace swa::recording {
namespace {

using mcap::kMagic;
namespace op = mcap::op;

const std::array<std::uint32_t, 256>& crcTable() {
  static const std::array<std::uint32_t, 256> table = [] {
    std::array<std::uint32_t, 256> t{};
    for (std::uint32_t n = 0; n < 256; ++n) {
      std::uint32_t c = n;
      for (int k = 0; k < 8; ++k) c = (c & 1u) != 0 ? 0xEDB88320u ^ (c >> 1) : c >> 1;
      t[n] = c;
    }
    return t;
  }();
  return table;
}

// Little-endian fields, as every MCAP record is.
class Bytes {
 public:
  Bytes& u8(std::uint8_t v) {
    b_.push_back(v);
    return *this;
  }
  Bytes& u16(std::uint16_t v) { return le(v, 2); }
  Bytes& u32(std::uint32_t v) { return le(v, 4); }
  Bytes& u64(std::uint64_t v) { return le(v, 8); }
  Bytes& str(std::string_view s) {
    u32(static_cast<std::uint32_t>(s.size()));
    return raw(reinterpret_cast<const std::uint8_t*>(s.data()), s.size());
  }
  Bytes& raw(const std::uint8_t* data, std::size_t size) {
    b_.insert(b_.end(), data, data + size);
    return *this;
  }
  Bytes& raw(const std::vector<std::uint8_t>& v) { return raw(v.data(), v.size()); }
  // A map or array field: its byte length, then its entries.
  Bytes& sized(const Bytes& entries) {
    u32(static_cast<std::uint32_t>(entries.b_.size()));
    return raw(entries.b_);
  }
  const std::vector<std::uint8_t>& bytes() const { return b_; }

 private:
  Bytes& le(std::uint64_t v, int n) {
    for (int i = 0; i < n; ++i) b_.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
    return *this;
  }
  std::vector<std::uint8_t> b_;
};

std::vector<std::uint8_t> record(std::uint8_t opcode, const Bytes& content) {
  Bytes r;
  r.u8(opcode).u64(content.bytes().size()).raw(content.bytes());
  return r.bytes();
}

}  // namespace

std::uint32_t crc32(const std::uint8_t* data, std::size_t size, std::uint32_t crc) {
  const auto& table = crcTable();
  crc = ~crc;
  for (std::size_t i = 0; i < size; ++i) crc = table[(crc ^ data[i]) & 0xFFu] ^ (crc >> 8);
  return ~crc;
}

McapWriter::McapWriter(const std::string& path, const Options& options) : options_(options), path_(path) {
  file_ = std::fopen(path.c_str(), "wb");
  if (file_ == nullptr) throw McapError("cannot create " + path + ": " + std::strerror(errno));
  put(std::vector<std::uint8_t>(kMagic.begin(), kMagic.end()));
  Bytes header;
  header.str(options_.profile).str(options_.library);
  put(record(op::kHeader, header));
  std::fflush(file_);
}

McapWriter::~McapWriter() {
  try {
    close();
  } catch (const McapError&) {
    // A destructor must not throw; close() reports the error to a caller who asks.
  }
  if (file_ != nullptr) std::fclose(file_);
}

std::vector<std::uint8_t> McapWriter::schemaRecord(const SchemaRecord& s) {
  Bytes c;
  c.u16(s.id).str(s.name).str(s.encoding).str(s.data);
  return record(op::kSchema, c);
}

std::vector<std::uint8_t> McapWriter::channelRecord(const ChannelRecord& ch) {
  Bytes metadata;
  for (const auto& [k, v] : ch.metadata) metadata.str(k).str(v);
  Bytes c;
  c.u16(ch.id).u16(ch.schema_id).str(ch.topic).str(ch.message_encoding).sized(metadata);
  return record(op::kChannel, c);
}

std::uint16_t McapWriter::addSchema(const std::string& name, const std::string& encoding, std::string_view data) {
  if (schemas_.size() >= 0xFFFEu) throw McapError(path_ + ": too many schemas");
  const auto id = static_cast<std::uint16_t>(schemas_.size() + 1);
  schemas_.push_back({id, name, encoding, std::string(data)});
  schema_in_chunk_stream_.push_back(false);
  return id;
}

std::uint16_t McapWriter::addChannel(std::uint16_t schema_id, const std::string& topic,
                                     const std::string& message_encoding,
                                     const std::map<std::string, std::string>& metadata) {
  if (schema_id > schemas_.size()) throw McapError(path_ + ": channel " + topic + " names an unknown schema");
  if (channels_.size() >= 0xFFFFu) throw McapError(path_ + ": too many channels");
  const auto id = static_cast<std::uint16_t>(channels_.size());
  channels_.push_back({id, schema_id, topic, message_encoding, metadata});
  channel_in_chunk_stream_.push_back(false);
  channel_counts_.push_back(0);
  return id;
}

std::uint64_t McapWriter::messageCount(std::uint16_t channel_id) const {
  return channel_id < channel_counts_.size() ? channel_counts_[channel_id] : 0;
}

void McapWriter::write(std::uint16_t channel_id, std::uint32_t sequence, std::uint64_t log_time_ns,
                       std::uint64_t publish_time_ns, const std::uint8_t* data, std::size_t size) {
  if (closed_) throw McapError(path_ + ": written after close");
  if (channel_id >= channels_.size()) throw McapError(path_ + ": message on an unknown channel");
  const ChannelRecord& ch = channels_[channel_id];
  // A streaming reader of a cut file needs the schema and channel before the message, in the same chunk stream.
  if (ch.schema_id != 0 && !schema_in_chunk_stream_[ch.schema_id - 1]) {
    const auto r = schemaRecord(schemas_[ch.schema_id - 1]);
    chunk_.insert(chunk_.end(), r.begin(), r.end());
    schema_in_chunk_stream_[ch.schema_id - 1] = true;
  }
  if (!channel_in_chunk_stream_[channel_id]) {
    const auto r = channelRecord(ch);
    chunk_.insert(chunk_.end(), r.begin(), r.end());
    channel_in_chunk_stream_[channel_id] = true;
  }
  chunk_index_[channel_id].emplace_back(log_time_ns, chunk_.size());
  Bytes m;
  m.u16(channel_id).u32(sequence).u64(log_time_ns).u64(publish_time_ns).raw(data, size);
  const auto r = record(op::kMessage, m);
  chunk_.insert(chunk_.end(), r.begin(), r.end());

  if (!chunk_has_messages_ || log_time_ns < chunk_start_ns_) chunk_start_ns_ = log_time_ns;
  if (!chunk_has_messages_ || log_time_ns > chunk_end_ns_) chunk_end_ns_ = log_time_ns;
  chunk_has_messages_ = true;
  if (message_count_ == 0 || log_time_ns < start_ns_) start_ns_ = log_time_ns;
  if (message_count_ == 0 || log_time_ns > end_ns_) end_ns_ = log_time_ns;
  ++message_count_;
  ++channel_counts_[channel_id];
  if (chunk_.size() >= options_.chunk_bytes) closeChunk();
}

void McapWriter::writeMetadata(const std::string& name, const std::map<std::string, std::string>& entries) {
  if (closed_) throw McapError(path_ + ": written after close");
  closeChunk();
  Bytes map;
  for (const auto& [k, v] : entries) map.str(k).str(v);
  Bytes c;
  c.str(name).sized(map);
  const auto r = record(op::kMetadata, c);
  metadata_indexes_.push_back({offset_, r.size(), name});
  put(r);
  if (std::fflush(file_) != 0) throw McapError("cannot write " + path_ + ": " + std::strerror(errno));
}

void McapWriter::put(const std::vector<std::uint8_t>& bytes) {
  if (std::fwrite(bytes.data(), 1, bytes.size(), file_) != bytes.size()) {
    throw McapError("cannot write " + path_ + ": " + std::strerror(errno));
  }
  data_crc_ = crc32(bytes.data(), bytes.size(), data_crc_);
  offset_ += bytes.size();
}

void McapWriter::closeChunk() {
  if (chunk_.empty()) return;
  ChunkIndex index{};
  index.start_ns = chunk_start_ns_;
  index.end_ns = chunk_end_ns_;
  index.offset = offset_;
  index.size = chunk_.size();
  Bytes c;
  c.u64(chunk_start_ns_).u64(chunk_end_ns_).u64(chunk_.size()).u32(crc32(chunk_.data(), chunk_.size()));
  c.str("");  // no compression: Debian's zstd/lz4 would do, but every reader handles an uncompressed chunk
  c.u64(chunk_.size()).raw(chunk_);
  const auto chunk_record = record(op::kChunk, c);
  index.length = chunk_record.size();
  put(chunk_record);

  const std::uint64_t indexes_start = offset_;
  for (const auto& [channel, entries] : chunk_index_) {
    Bytes list;
    for (const auto& [log_time, offset] : entries) list.u64(log_time).u64(offset);
    Bytes mi;
    mi.u16(channel).sized(list);
    index.index_offsets[channel] = offset_;
    put(record(op::kMessageIndex, mi));
  }
  index.index_length = offset_ - indexes_start;
  chunk_indexes_.push_back(std::move(index));

  chunk_.clear();
  chunk_index_.clear();
  chunk_has_messages_ = false;
  if (std::fflush(file_) != 0) throw McapError("cannot write " + path_ + ": " + std::strerror(errno));
}

void McapWriter::close() {
  if (closed_) return;
  closed_ = true;
  closeChunk();
  Bytes data_end;
  data_end.u32(data_crc_);
  put(record(op::kDataEnd, data_end));

  // The summary: its bytes, and from the Summary Offsets on, the footer's CRC.
  const std::uint64_t summary_start = offset_;
  std::vector<std::uint8_t> summary;
  struct Group {
    std::uint8_t opcode;
    std::uint64_t start, length;
  };
  std::vector<Group> groups;
  const auto group = [&](std::uint8_t opcode, const std::vector<std::vector<std::uint8_t>>& records) {
    if (records.empty()) return;
    Group g{opcode, summary_start + summary.size(), 0};
    for (const auto& r : records) summary.insert(summary.end(), r.begin(), r.end());
    g.length = summary_start + summary.size() - g.start;
    groups.push_back(g);
  };
  std::vector<std::vector<std::uint8_t>> records;
  for (const SchemaRecord& s : schemas_) records.push_back(schemaRecord(s));
  group(op::kSchema, records);
  records.clear();
  for (const ChannelRecord& ch : channels_) records.push_back(channelRecord(ch));
  group(op::kChannel, records);

  Bytes counts;
  for (std::size_t i = 0; i < channel_counts_.size(); ++i)
    counts.u16(static_cast<std::uint16_t>(i)).u64(channel_counts_[i]);
  Bytes stats;
  stats.u64(message_count_)
      .u16(static_cast<std::uint16_t>(schemas_.size()))
      .u32(static_cast<std::uint32_t>(channels_.size()));
  stats.u32(0).u32(static_cast<std::uint32_t>(metadata_indexes_.size()));  // attachments, metadata
  stats.u32(static_cast<std::uint32_t>(chunk_indexes_.size()));
  stats.u64(message_count_ > 0 ? start_ns_ : 0).u64(message_count_ > 0 ? end_ns_ : 0).sized(counts);
  group(op::kStatistics, {record(op::kStatistics, stats)});

  records.clear();
  for (const ChunkIndex& ci : chunk_indexes_) {
    Bytes offsets;
    for (const auto& [channel, offset] : ci.index_offsets) offsets.u16(channel).u64(offset);
    Bytes r;
    r.u64(ci.start_ns).u64(ci.end_ns).u64(ci.offset).u64(ci.length).sized(offsets).u64(ci.index_length);
    r.str("").u64(ci.size).u64(ci.size);
    records.push_back(record(op::kChunkIndex, r));
  }
  group(op::kChunkIndex, records);
  records.clear();
  for (const MetadataIndex& mi : metadata_indexes_) {
    Bytes r;
    r.u64(mi.offset).u64(mi.length).str(mi.name);
    records.push_back(record(op::kMetadataIndex, r));
  }
  group(op::kMetadataIndex, records);

  const std::uint64_t summary_offset_start = summary_start + summary.size();
  for (const Group& g : groups) {
    Bytes so;
    so.u8(g.opcode).u64(g.start).u64(g.length);
    const auto r = record(op::kSummaryOffset, so);
    summary.insert(summary.end(), r.begin(), r.end());
  }
  // The footer's CRC covers the summary, the summary offsets, and the footer up to the CRC itself.
  Bytes footer_head;
  footer_head.u8(op::kFooter).u64(8 + 8 + 4).u64(summary_start).u64(summary_offset_start);
  std::uint32_t crc = crc32(summary.data(), summary.size());
  crc = crc32(footer_head.bytes().data(), footer_head.bytes().size(), crc);
  footer_head.u32(crc).raw(kMagic.data(), kMagic.size());
  put(summary);
  put(footer_head.bytes());
  const int flushed = std::fflush(file_);
  const int closed = std::fclose(file_);
  file_ = nullptr;
  if (flushed != 0 || closed != 0) throw McapError("cannot write " + path_ + ": " + std::strerror(errno));
}

}  // namespace swa::recording

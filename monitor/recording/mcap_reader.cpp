#include "swa/recording/mcap_reader.h"

#include <array>

#include "mcap_format.h"

namespace swa::recording {
namespace {

using mcap::kMagic;
namespace op = mcap::op;
// Largest record accepted: a chunk of another writer may be big, but not this big.
constexpr std::uint64_t kMaxRecord = 1ull << 30;

// Little-endian fields of one record's content; every read is bounds-checked.
class Fields {
 public:
  Fields(const std::uint8_t* data, std::size_t size, const std::string& what) : p_(data), n_(size), what_(what) {}
  std::uint64_t uint(int bytes) {
    need(static_cast<std::size_t>(bytes));
    std::uint64_t v = 0;
    for (int i = bytes - 1; i >= 0; --i) v = (v << 8) | p_[at_ + static_cast<std::size_t>(i)];
    at_ += static_cast<std::size_t>(bytes);
    return v;
  }
  std::string str() {
    const auto size = static_cast<std::size_t>(uint(4));
    need(size);
    std::string s(reinterpret_cast<const char*>(p_ + at_), size);
    at_ += size;
    return s;
  }
  std::map<std::string, std::string> stringMap() {
    const auto size = static_cast<std::size_t>(uint(4));
    need(size);
    Fields entries(p_ + at_, size, what_);
    at_ += size;
    std::map<std::string, std::string> m;
    while (!entries.empty()) {
      std::string k = entries.str();
      m[k] = entries.str();
    }
    return m;
  }
  const std::uint8_t* here() const { return p_ + at_; }
  std::size_t left() const { return n_ - at_; }
  bool empty() const { return at_ == n_; }
  void skip(std::size_t size) {
    need(size);
    at_ += size;
  }

 private:
  void need(std::size_t size) const {
    if (size > n_ - at_) throw McapError("malformed " + what_ + ": a field runs past the end of its record");
  }
  const std::uint8_t* p_;
  std::size_t n_;
  std::size_t at_ = 0;
  std::string what_;
};

}  // namespace

McapReader::McapReader(const std::string& path) : path_(path), in_(path, std::ios::binary) {
  if (!in_) throw McapError("cannot read " + path);
  std::array<std::uint8_t, 8> magic{};
  in_.read(reinterpret_cast<char*>(magic.data()), magic.size());
  if (!in_ || magic != kMagic) throw McapError(path + " is not an MCAP file (no MCAP magic)");
  std::uint8_t opcode = 0;
  std::vector<std::uint8_t> content;
  if (!nextRecord(opcode, content) || opcode != op::kHeader) throw McapError(path + ": no MCAP Header record");
  Fields f(content.data(), content.size(), path + " Header");
  profile_ = f.str();
}

bool McapReader::nextRecord(std::uint8_t& opcode, std::vector<std::uint8_t>& content) {
  std::array<std::uint8_t, 9> prefix{};
  in_.read(reinterpret_cast<char*>(prefix.data()), prefix.size());
  if (in_.gcount() != static_cast<std::streamsize>(prefix.size())) {
    truncated_ = true;
    return false;
  }
  opcode = prefix[0];
  Fields length(prefix.data() + 1, 8, path_);
  const std::uint64_t size = length.uint(8);
  if (size > kMaxRecord) throw McapError(path_ + ": a record of " + std::to_string(size) + " bytes");
  content.resize(static_cast<std::size_t>(size));
  in_.read(reinterpret_cast<char*>(content.data()), static_cast<std::streamsize>(size));
  if (in_.gcount() != static_cast<std::streamsize>(size)) {
    truncated_ = true;  // the writer died while writing this record
    return false;
  }
  return true;
}

void McapReader::take(std::uint8_t opcode, const std::vector<std::uint8_t>& content, std::optional<Message>& message) {
  Fields f(content.data(), content.size(), path_ + " record");
  if (opcode == op::kSchema) {
    Schema s;
    s.id = static_cast<std::uint16_t>(f.uint(2));
    s.name = f.str();
    s.encoding = f.str();
    s.data = f.str();
    schemas_[s.id] = std::move(s);
  } else if (opcode == op::kChannel) {
    Channel c;
    c.id = static_cast<std::uint16_t>(f.uint(2));
    c.schema_id = static_cast<std::uint16_t>(f.uint(2));
    c.topic = f.str();
    c.message_encoding = f.str();
    channels_[c.id] = std::move(c);
  } else if (opcode == op::kMetadata) {
    std::string name = f.str();
    metadata_[name] = f.stringMap();
  } else if (opcode == op::kMessage) {
    Message m;
    m.channel_id = static_cast<std::uint16_t>(f.uint(2));
    m.sequence = static_cast<std::uint32_t>(f.uint(4));
    m.log_time_ns = f.uint(8);
    m.publish_time_ns = f.uint(8);
    if (channels_.count(m.channel_id) == 0) {
      throw McapError(path_ + ": a message on channel " + std::to_string(m.channel_id) + " before its Channel record");
    }
    m.data.assign(f.here(), f.here() + f.left());
    message = std::move(m);
  }
  // Every other record (indexes, statistics, attachments) says nothing a streaming reader needs.
}

std::optional<McapReader::Message> McapReader::next() {
  std::optional<Message> message;
  while (!message) {
    if (chunk_pos_ < chunk_.size()) {
      Fields f(chunk_.data() + chunk_pos_, chunk_.size() - chunk_pos_, path_ + " chunk");
      const auto opcode = static_cast<std::uint8_t>(f.uint(1));
      const std::uint64_t size = f.uint(8);
      if (size > f.left()) throw McapError(path_ + ": a record runs past the end of its chunk");
      const std::vector<std::uint8_t> content(f.here(), f.here() + size);
      chunk_pos_ += 9 + static_cast<std::size_t>(size);
      take(opcode, content, message);
      continue;
    }
    if (done_) return std::nullopt;
    std::uint8_t opcode = 0;
    std::vector<std::uint8_t> content;
    if (!nextRecord(opcode, content)) {
      done_ = true;
      return std::nullopt;
    }
    if (opcode == op::kDataEnd || opcode == op::kFooter) {
      done_ = true;
      return std::nullopt;
    }
    if (opcode == op::kChunk) {
      Fields f(content.data(), content.size(), path_ + " Chunk");
      f.skip(8 + 8 + 8 + 4);  // start and end time, uncompressed size and CRC
      const std::string compression = f.str();
      if (!compression.empty()) {
        throw McapError(path_ + ": a chunk compressed with " + compression + " (only uncompressed chunks are read)");
      }
      const std::uint64_t size = f.uint(8);
      if (size != f.left()) throw McapError(path_ + ": a chunk's records do not fill it");
      chunk_.assign(f.here(), f.here() + size);
      chunk_pos_ = 0;
      continue;
    }
    take(opcode, content, message);
  }
  return message;
}

}  // namespace swa::recording

#pragma once
// The constants of the MCAP format (https://mcap.dev/spec) shared by mcap_writer.cpp and mcap_reader.cpp.

#include <array>
#include <cstdint>

namespace swa::recording::mcap {

constexpr std::array<std::uint8_t, 8> kMagic = {0x89, 'M', 'C', 'A', 'P', '0', '\r', '\n'};

// Record opcodes.
namespace op {
constexpr std::uint8_t kHeader = 0x01;
constexpr std::uint8_t kFooter = 0x02;
constexpr std::uint8_t kSchema = 0x03;
constexpr std::uint8_t kChannel = 0x04;
constexpr std::uint8_t kMessage = 0x05;
constexpr std::uint8_t kChunk = 0x06;
constexpr std::uint8_t kMessageIndex = 0x07;
constexpr std::uint8_t kChunkIndex = 0x08;
constexpr std::uint8_t kStatistics = 0x0B;
constexpr std::uint8_t kMetadata = 0x0C;
constexpr std::uint8_t kMetadataIndex = 0x0D;
constexpr std::uint8_t kSummaryOffset = 0x0E;
constexpr std::uint8_t kDataEnd = 0x0F;
}  // namespace op

}  // namespace swa::recording::mcap

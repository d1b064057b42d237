// The MCAP writer (swa/recording/mcap_writer.h) byte for byte where the format fixes the bytes, the recording around it
// (recording.h), the message definitions it stores (swa/msg_defs) and the monitor's metrics messages. The whole file
// against the reference reader: tests/record/test_mcap_record.sh.

#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "scratch.h"
#include "step_metrics_json.h"
#include "swa/msg_defs/ros_definition.h"
#include "swa/recording/mcap_reader.h"
#include "swa/recording/mcap_writer.h"
#include "swa/recording/recording.h"

namespace swa::recording {
namespace {

namespace fs = std::filesystem;
using Bytes = std::vector<std::uint8_t>;

const Bytes kMagic = {0x89, 'M', 'C', 'A', 'P', '0', '\r', '\n'};

std::uint64_t le(const Bytes& b, std::size_t at, int n) {
  std::uint64_t v = 0;
  for (int i = n - 1; i >= 0; --i) v = (v << 8) | b.at(at + i);
  return v;
}

Bytes readFile(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return Bytes(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// Opcodes of the records in [begin, end).
std::vector<int> opcodes(const Bytes& b, std::size_t begin, std::size_t end) {
  std::vector<int> ops;
  while (begin < end) {
    ops.push_back(b.at(begin));
    begin += 9 + le(b, begin + 1, 8);
  }
  return ops;
}

class McapWriterTest : public ::testing::Test {
 protected:
  swa::testing::ScratchDir dir_{"swa_test_mcap"};
};

TEST(Crc32, MatchesTheCheckValueOfCrc32IsoHdlc) {
  const std::string text = "123456789";
  const auto* p = reinterpret_cast<const std::uint8_t*>(text.data());
  EXPECT_EQ(crc32(p, text.size()), 0xCBF43926u);
  EXPECT_EQ(crc32(p + 4, 5, crc32(p, 4)), 0xCBF43926u) << "a CRC continued over two calls";
  EXPECT_EQ(crc32(p, 0), 0u);
}

TEST_F(McapWriterTest, FileHasMagicHeaderDataEndSummaryAndAFooterWhoseOffsetsAndCrcsHold) {
  const fs::path path = dir_ / "a.mcap";
  {
    McapWriter w(path.string(), {"ros2", "swa", 1 << 20});
    const std::uint16_t schema = w.addSchema("swa_msgs/msg/Imu", "ros2msg", "float64 x\n");
    const std::uint16_t channel = w.addChannel(schema, "/swa/uav0/imu", "cdr", {{"k", "v"}});
    const Bytes payload = {0, 1, 0, 0, 42};
    w.write(channel, 7, 1000, 2000, payload.data(), payload.size());
    w.close();
    EXPECT_EQ(w.messageCount(), 1u);
    EXPECT_EQ(w.chunkCount(), 1u);
  }
  const Bytes b = readFile(path);
  ASSERT_GT(b.size(), 2 * kMagic.size() + 29);
  EXPECT_TRUE(std::equal(kMagic.begin(), kMagic.end(), b.begin()));
  EXPECT_TRUE(std::equal(kMagic.begin(), kMagic.end(), b.end() - 8));
  EXPECT_EQ(b[8], 0x01) << "the Header follows the magic";

  // Footer: opcode, length 20, summary start, summary offset start, summary CRC; then the magic.
  const std::size_t footer = b.size() - 8 - 29;
  ASSERT_EQ(b[footer], 0x02);
  EXPECT_EQ(le(b, footer + 1, 8), 20u);
  const std::uint64_t summary_start = le(b, footer + 9, 8);
  const std::uint64_t summary_offsets = le(b, footer + 17, 8);
  EXPECT_EQ(crc32(b.data() + summary_start, footer + 25 - summary_start), le(b, footer + 25, 4))
      << "the summary CRC covers the summary, its offsets and the footer up to the CRC";

  // Data End right before the summary, with the CRC of everything before it.
  const std::size_t data_end = summary_start - 13;
  ASSERT_EQ(b.at(data_end), 0x0F);
  EXPECT_EQ(crc32(b.data(), data_end), le(b, data_end + 9, 4));

  // Data section: Header, one Chunk, one Message Index; summary: Schema, Channel, Statistics, Chunk Index; then one
  // Summary Offset per group.
  EXPECT_EQ(opcodes(b, 8, data_end), (std::vector<int>{0x01, 0x06, 0x07}));
  EXPECT_EQ(opcodes(b, summary_start, summary_offsets), (std::vector<int>{0x03, 0x04, 0x0B, 0x08}));
  EXPECT_EQ(opcodes(b, summary_offsets, footer), (std::vector<int>{0x0E, 0x0E, 0x0E, 0x0E}));
}

TEST_F(McapWriterTest, EachChunkCarriesTheSchemaAndChannelBeforeTheirFirstMessageSoACutFileStillReads) {
  const fs::path path = dir_ / "b.mcap";
  McapWriter w(path.string(), {"ros2", "swa", 200});
  const std::uint16_t schema = w.addSchema("s", "jsonschema", "{}");
  const std::uint16_t a = w.addChannel(schema, "/a", "json");
  const Bytes payload(100, '1');
  for (int i = 0; i < 10; ++i) w.write(a, i, 10 * i, 0, payload.data(), payload.size());
  EXPECT_GE(w.chunkCount(), 4u) << "a chunk is closed once it holds chunk_bytes";
  const std::uint32_t closed = w.chunkCount();
  const Bytes before_close = readFile(path);
  // The first chunk's records: Schema, Channel, then messages. Chunk content: 3 u64 + crc + compression "" + u64.
  const std::size_t chunk = 8 + 9 + le(before_close, 9, 8);
  ASSERT_EQ(before_close.at(chunk), 0x06);
  const std::size_t records = chunk + 9 + 8 + 8 + 8 + 4 + 4 + 8;
  const std::size_t records_end = records + le(before_close, records - 8, 8);
  const std::vector<int> ops = opcodes(before_close, records, records_end);
  ASSERT_GE(ops.size(), 3u);
  EXPECT_EQ(ops[0], 0x03);
  EXPECT_EQ(ops[1], 0x04);
  EXPECT_EQ(ops[2], 0x05);
  EXPECT_EQ(le(before_close, records - 8 - 4 - 4, 4), crc32(before_close.data() + records, records_end - records))
      << "the chunk's CRC of its records";
  w.close();
  EXPECT_EQ(w.messageCount(a), 10u);
  EXPECT_GE(w.chunkCount(), closed);
}

TEST_F(McapWriterTest, RefusesUnknownChannelsAndSchemasAndAnUnwritablePath) {
  McapWriter w((dir_ / "c.mcap").string(), {});
  const Bytes payload = {1};
  EXPECT_THROW(w.write(0, 0, 0, 0, payload.data(), payload.size()), McapError);
  EXPECT_THROW(w.addChannel(3, "/x", "cdr"), McapError);
  try {
    McapWriter bad((dir_ / "no" / "such" / "dir.mcap").string(), {});
    FAIL() << "created a file in a missing directory";
  } catch (const McapError& e) {
    EXPECT_NE(std::string(e.what()).find("dir.mcap"), std::string::npos) << e.what();
  }
  w.close();
  EXPECT_THROW(w.write(0, 0, 0, 0, payload.data(), payload.size()), McapError);
}

TEST_F(McapWriterTest, ReaderGetsBackEveryMessageMetadataAndDeclarationAndStopsCleanlyInACutFile) {
  const fs::path path = dir_ / "d.mcap";
  {
    McapWriter w(path.string(), {"ros2", "swa", 300});
    const std::uint16_t schema = w.addSchema("swa_msgs/msg/Imu", "ros2msg", "float64 x\n");
    const std::uint16_t a = w.addChannel(schema, "/a", "cdr");
    w.writeMetadata("swa_scenario", {{"scenario.yaml", "seed: 3\n"}});
    const std::uint16_t b = w.addChannel(0, "/b", "json");
    for (std::uint8_t i = 0; i < 20; ++i) {
      const Bytes payload(50, i);
      w.write(i % 2 == 0 ? a : b, i, 100u * i, 7, payload.data(), payload.size());
    }
    w.close();
  }
  {
    McapReader r(path.string());
    EXPECT_EQ(r.profile(), "ros2");
    int n = 0;
    while (auto m = r.next()) {
      EXPECT_EQ(m->channel_id, n % 2 == 0 ? 0 : 1);
      EXPECT_EQ(m->sequence, static_cast<std::uint32_t>(n));
      EXPECT_EQ(m->log_time_ns, 100u * n);
      EXPECT_EQ(m->data, Bytes(50, static_cast<std::uint8_t>(n)));
      ++n;
    }
    EXPECT_EQ(n, 20);
    EXPECT_FALSE(r.truncated());
    EXPECT_EQ(r.channels().at(1).topic, "/b");
    EXPECT_EQ(r.schemas().at(1).name, "swa_msgs/msg/Imu");
    EXPECT_EQ(r.metadata().at("swa_scenario").at("scenario.yaml"), "seed: 3\n");
  }
  // Cut in the middle: the whole chunks before the cut, then the end, flagged.
  const Bytes whole = readFile(path);
  const fs::path cut = dir_ / "cut.mcap";
  std::ofstream(cut, std::ios::binary)
      .write(reinterpret_cast<const char*>(whole.data()), static_cast<std::streamsize>(whole.size() / 2));
  McapReader r(cut.string());
  int n = 0;
  while (auto m = r.next()) {
    EXPECT_EQ(m->sequence, static_cast<std::uint32_t>(n));
    ++n;
  }
  EXPECT_TRUE(r.truncated());
  EXPECT_GT(n, 0);
  EXPECT_LT(n, 20);

  std::ofstream(dir_ / "not.mcap") << "hello, this is not MCAP";
  EXPECT_THROW(McapReader((dir_ / "not.mcap").string()), McapError);
}

TEST(RosDefinition, AppendsEveryUsedTypeOnceAfterTheMessageItself) {
  const std::optional<std::string> truth = msg_defs::rosDefinition("SwarmTruth");
  ASSERT_TRUE(truth);
  const std::string separator = std::string(80, '=') + "\nMSG: ";
  EXPECT_EQ(truth->rfind(std::string(*msg_defs::msgText("SwarmTruth")), 0), 0u) << "the message's own .msg first";
  for (const char* dependency : {"MessageHeader", "UavTruth"}) {
    const std::string header = separator + "swa_msgs/" + dependency + "\n";
    const std::size_t at = truth->find(header);
    ASSERT_NE(at, std::string::npos) << dependency;
    EXPECT_EQ(truth->find(header, at + 1), std::string::npos) << dependency << " twice";
    EXPECT_EQ(truth->compare(at + header.size(), msg_defs::msgText(dependency)->size(),
                             std::string(*msg_defs::msgText(dependency))),
              0);
  }
  const std::optional<std::string> detections = msg_defs::rosDefinition("Detections");
  ASSERT_TRUE(detections);
  EXPECT_NE(detections->find(separator + "swa_msgs/Detection\n"), std::string::npos);
  EXPECT_EQ(*msg_defs::rosDefinition("MessageHeader"), std::string(*msg_defs::msgText("MessageHeader")))
      << "a message of primitives only has nothing appended";
  EXPECT_FALSE(msg_defs::rosDefinition("NoSuchType"));
  EXPECT_EQ(msg_defs::rosTypeName("Imu"), "swa_msgs/msg/Imu");
}

TEST(RosDefinition, EveryMessageOfTheInterfacePackageResolves) {
  const std::vector<std::string> names = msg_defs::typeNames();
  EXPECT_EQ(names.size(), 16u);  // message set 6 added MissionLeg and SwarmMission
  for (const std::string& name : names) EXPECT_NO_THROW(EXPECT_TRUE(msg_defs::rosDefinition(name))) << name;
}

Bytes headerPayload(bool little, std::int64_t stamp, std::uint32_t seq) {
  Bytes b = {0x00, static_cast<std::uint8_t>(little ? 0x01 : 0x00), 0x00, 0x00};
  for (int i = 0; i < 8; ++i) {
    const int shift = little ? 8 * i : 8 * (7 - i);
    b.push_back(static_cast<std::uint8_t>(static_cast<std::uint64_t>(stamp) >> shift));
  }
  for (int i = 0; i < 4; ++i) b.push_back(static_cast<std::uint8_t>(seq >> (little ? 8 * i : 8 * (3 - i))));
  return b;
}

TEST(PayloadStamp, ReadsTheMessageHeaderInEitherByteOrderAndRejectsWhatIsNotOne) {
  const Bytes le_payload = headerPayload(true, 1'500'000'000, 17);
  auto s = payloadStamp(le_payload.data(), le_payload.size());
  ASSERT_TRUE(s);
  EXPECT_EQ(s->stamp_ns, 1'500'000'000u);
  EXPECT_EQ(s->seq, 17u);
  const Bytes be_payload = headerPayload(false, 42, 3);
  s = payloadStamp(be_payload.data(), be_payload.size());
  ASSERT_TRUE(s);
  EXPECT_EQ(s->stamp_ns, 42u);
  EXPECT_EQ(s->seq, 3u);
  EXPECT_FALSE(payloadStamp(le_payload.data(), le_payload.size() - 1)) << "too short";
  const Bytes negative = headerPayload(true, -5, 1);
  EXPECT_FALSE(payloadStamp(negative.data(), negative.size()));
  Bytes pl_cdr = le_payload;
  pl_cdr[1] = 0x03;  // PL_CDR_LE: a parameter list, not SWA's encoding
  EXPECT_FALSE(payloadStamp(pl_cdr.data(), pl_cdr.size()));
}

TEST_F(McapWriterTest, RecordingCountsPerChannelClosesOldChunksAndWritesItsManifest) {
  const fs::path path = dir_ / "r.mcap";
  Recording recording(path.string(), {1 << 20, 1.0});
  const std::uint16_t imu = recording.cdrChannel("/swa/uav0/imu", "Imu");
  EXPECT_EQ(recording.cdrChannel("/swa/uav0/imu", "Imu"), imu) << "one channel per topic";
  EXPECT_THROW(recording.cdrChannel("/x", "NoSuchType"), McapError);
  recording.writeCdr(imu, headerPayload(true, 100, 1), 5);
  recording.writeCdr(imu, Bytes{1, 2}, 7);  // no header: written with its publish time, counted
  const auto size_before = fs::file_size(path);
  recording.tick(std::chrono::steady_clock::now());
  EXPECT_EQ(fs::file_size(path), size_before) << "a young chunk stays open";
  recording.tick(std::chrono::steady_clock::now() + std::chrono::seconds(2));
  EXPECT_GT(fs::file_size(path), size_before) << "a chunk older than chunk_max_age_s is written";
  const std::uint16_t metrics = recording.jsonChannel("/m", "schema", "{}");
  recording.writeJson(metrics, "{}", 1, 1);
  recording.close();
  recording.writeJson(metrics, "{}", 2, 2);  // after close: dropped
  EXPECT_EQ(recording.unstamped(), 1u);

  writeRecordingManifest((dir_ / "recording.json").string(), recording);
  const auto manifest = nlohmann::json::parse(std::ifstream(dir_ / "recording.json"));
  EXPECT_EQ(manifest["profile"], "ros2");
  EXPECT_EQ(manifest["channels"]["/swa/uav0/imu"]["schema"], "swa_msgs/msg/Imu");
  EXPECT_EQ(manifest["channels"]["/swa/uav0/imu"]["schema_encoding"], "ros2msg");
  EXPECT_EQ(manifest["channels"]["/swa/uav0/imu"]["messages"], 2);
  EXPECT_EQ(manifest["channels"]["/m"]["message_encoding"], "json");
  EXPECT_EQ(manifest["channels"]["/m"]["messages"], 1);
}

// A reader created again with a re-created participant is sent its writers' history once more: what it took before
// is not recorded twice, what it missed in between is.
TEST_F(McapWriterTest, RecordingTakesEachSampleOfAWriterOnceAndCountsTheRepeats) {
  Recording recording((dir_ / "r.mcap").string(), {1 << 20, 1.0});
  const Recording::WriterId a{1, 2, 3}, b{9};
  EXPECT_TRUE(recording.firstDelivery(7, a, 1));
  EXPECT_TRUE(recording.firstDelivery(7, a, 2));
  EXPECT_TRUE(recording.firstDelivery(7, b, 1)) << "another writer numbers its own samples";
  EXPECT_TRUE(recording.firstDelivery(8, a, 1)) << "another reader (channel) keeps its own account";
  // the history again, then what was missed meanwhile
  EXPECT_FALSE(recording.firstDelivery(7, a, 1));
  EXPECT_FALSE(recording.firstDelivery(7, a, 2));
  EXPECT_TRUE(recording.firstDelivery(7, a, 5));
  EXPECT_FALSE(recording.firstDelivery(7, a, 4)) << "behind the newest taken: a repeat";
  EXPECT_EQ(recording.repeats(), 3u);
  recording.close();
  writeRecordingManifest((dir_ / "recording.json").string(), recording);
  EXPECT_EQ(nlohmann::json::parse(std::ifstream(dir_ / "recording.json"))["repeats"], 3);
}

TEST(StepMetricsJson, EveryColumnOfTheTimeSeriesWithNullForAnUndefinedValue) {
  monitor::TimeSeriesRow row;
  row.t_s = 12.5;
  row.d_nb_m = 9.75;
  row.collisions = 2;
  row.groups = 1;
  const auto j = nlohmann::json::parse(monitor_node::stepMetricsJson(row));
  EXPECT_EQ(j["t_s"], 12.5);
  EXPECT_EQ(j["d_nb_m"], 9.75);
  EXPECT_TRUE(j["nees_pos"].is_null()) << "NaN is not JSON";
  EXPECT_EQ(j["collisions"], 2);
  const auto schema = nlohmann::json::parse(monitor_node::stepMetricsJsonSchema());
  EXPECT_EQ(schema["required"].size(), j.size()) << "every field required";
  for (const auto& key : schema["required"]) EXPECT_TRUE(j.contains(key)) << key;
}

}  // namespace
}  // namespace swa::recording

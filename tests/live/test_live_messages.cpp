// The live view's pure parts (monitor/live_view): the Foxglove protocol's messages and frames, the client requests
// it accepts, and the swarm / agent-state payloads. The server over a socket: tests/live/test_live_view.sh.

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "foxglove_protocol.h"
#include "live_messages.h"

namespace swa::live {
namespace {

using Json = nlohmann::json;

TEST(FoxgloveProtocol, SelectsTheFirstRequestedSubprotocolItSpeaksAndNoOther) {
  EXPECT_EQ(selectSubprotocol({"foxglove.websocket.v1"}), "foxglove.websocket.v1");
  EXPECT_EQ(selectSubprotocol({"foxglove.sdk.v1"}), "foxglove.sdk.v1");
  EXPECT_EQ(selectSubprotocol({"chat", "foxglove.sdk.v1", "foxglove.websocket.v1"}), "foxglove.sdk.v1");
  EXPECT_FALSE(selectSubprotocol({}));
  EXPECT_FALSE(selectSubprotocol({"foxglove.websocket.v2", "ros2"}));
}

TEST(FoxgloveProtocol, ServerInfoAndAdvertiseCarryWhatTheSpecRequires) {
  const Json info = Json::parse(serverInfoJson("swa_monitor", "42"));
  EXPECT_EQ(info["op"], "serverInfo");
  EXPECT_EQ(info["name"], "swa_monitor");
  EXPECT_TRUE(info["capabilities"].is_array());
  const Json ad = Json::parse(advertiseJson({{3, "/a", "s/A", "{\"type\":\"object\"}"}}));
  EXPECT_EQ(ad["op"], "advertise");
  ASSERT_EQ(ad["channels"].size(), 1u);
  EXPECT_EQ(ad["channels"][0]["id"], 3);
  EXPECT_EQ(ad["channels"][0]["topic"], "/a");
  EXPECT_EQ(ad["channels"][0]["encoding"], "json");
  EXPECT_EQ(ad["channels"][0]["schemaEncoding"], "jsonschema");
  EXPECT_EQ(ad["channels"][0]["schema"], "{\"type\":\"object\"}") << "the schema is a string, not an object";
}

TEST(FoxgloveProtocol, MessageDataFrameIsOpcodeSubscriptionTimestampPayloadLittleEndian) {
  const std::vector<std::uint8_t> f = messageDataFrame(0x01020304u, 0x1122334455667788ull, "{}");
  const std::vector<std::uint8_t> want = {0x01, 0x04, 0x03, 0x02, 0x01, 0x88, 0x77, 0x66,
                                          0x55, 0x44, 0x33, 0x22, 0x11, '{',  '}'};
  EXPECT_EQ(f, want);
}

TEST(FoxgloveProtocol, SubscribeAndUnsubscribeParsedAnythingElseAnsweredNotObeyed) {
  const ClientRequest s =
      parseClientRequest(R"({"op":"subscribe","subscriptions":[{"id":0,"channelId":2},{"id":1,"channelId":5}]})");
  ASSERT_TRUE(std::holds_alternative<Subscribe>(s));
  using Pairs = std::vector<std::pair<std::uint32_t, std::uint32_t>>;
  EXPECT_EQ(std::get<Subscribe>(s).subscriptions, (Pairs{{0, 2}, {1, 5}}));
  const ClientRequest u = parseClientRequest(R"({"op":"unsubscribe","subscriptionIds":[1]})");
  ASSERT_TRUE(std::holds_alternative<Unsubscribe>(u));
  EXPECT_EQ(std::get<Unsubscribe>(u).subscription_ids, std::vector<std::uint32_t>{1});
  for (const char* bad : {"not json", "[]", R"({"op":"advertise"})", R"({"op":"subscribe"})",
                          R"({"op":"subscribe","subscriptions":[{"id":-1,"channelId":2}]})",
                          R"({"op":"subscribe","subscriptions":[{"id":4294967296,"channelId":2}]})",
                          R"({"op":"unsubscribe","subscriptionIds":["x"]})"}) {
    EXPECT_TRUE(std::holds_alternative<Unsupported>(parseClientRequest(bad))) << bad;
  }
}

monitor_node::StateSample state(int uav, double x, double y, std::vector<int> neighbours) {
  monitor_node::StateSample s;
  s.uav = uav;
  s.stamp_ns = 2'000'000'000;
  s.mode = agent::Mode::kSwa;
  s.estimate.valid = true;
  s.estimate.position_m = {x, y};
  s.estimate.neighbour_count = static_cast<int>(neighbours.size());
  for (std::size_t k = 0; k < neighbours.size(); ++k) s.estimate.neighbour_ids[k] = neighbours[k];
  return s;
}

TEST(LiveMessages, SwarmHasEveryUavEachLinkOnceAndEachCentreAtTruthMinusEstimate) {
  monitor_node::TruthSample truth;
  truth.stamp_ns = 2'500'000'000;
  for (int i = 0; i < 3; ++i) {
    monitor::UavTruth u;
    u.id = i;
    u.position_m = {10.0 * i, 1.0};
    u.velocity_mps = {0.5, std::nan("")};
    truth.uavs.push_back(u);
    truth.agent_alive.push_back(i != 2);
  }
  std::map<int, monitor_node::StateSample> latest;
  latest[0] = state(0, 1.0, 2.0, {1, 2});
  latest[1] = state(1, -1.0, 0.0, {0, 7});  // 7: not in the truth, no link
  latest[2] = state(2, 0.0, 0.0, {});
  latest[2].estimate.valid = false;  // no centre, no link
  const Json j = Json::parse(swarmJson(swarmScene(truth, latest)));
  EXPECT_DOUBLE_EQ(j["t_s"].get<double>(), 2.5);
  ASSERT_EQ(j["uavs"].size(), 3u);
  EXPECT_EQ(j["uavs"][1]["x_m"], 10.0);
  EXPECT_TRUE(j["uavs"][1]["vy_mps"].is_null()) << "NaN is null";
  EXPECT_EQ(j["uavs"][2]["agent_alive"], false);
  EXPECT_EQ(j["links"], Json::parse("[[0,1],[0,2]]"));
  ASSERT_EQ(j["centres"].size(), 2u);
  EXPECT_EQ(j["centres"][0]["uav"], 0);
  EXPECT_EQ(j["centres"][0]["x_m"], -1.0);
  EXPECT_EQ(j["centres"][0]["y_m"], -1.0);
  EXPECT_EQ(j["centres"][1]["x_m"], 11.0);

  const Json s = Json::parse(agentStateJson(latest[0]));
  EXPECT_EQ(s["mode"], "swa");
  EXPECT_EQ(s["neighbours"], Json::parse("[1,2]"));
  EXPECT_EQ(agentStateTopic(3), "/swa/live/uav3/state");
  const Json schema = Json::parse(swarmJsonSchema());
  for (const auto& key : schema["required"]) EXPECT_TRUE(j.contains(key)) << key;
}

}  // namespace
}  // namespace swa::live

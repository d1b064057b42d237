#include "foxglove_protocol.h"

#include <algorithm>

#include <nlohmann/json.hpp>

namespace swa::live {
namespace {

using Json = nlohmann::ordered_json;

}  // namespace

std::optional<std::string> selectSubprotocol(const std::vector<std::string>& requested) {
  for (const std::string& r : requested) {
    if (std::find(std::begin(kSubprotocols), std::end(kSubprotocols), r) != std::end(kSubprotocols)) return r;
  }
  return std::nullopt;
}

std::string serverInfoJson(const std::string& name, const std::string& session_id) {
  return Json{{"op", "serverInfo"},
              {"name", name},
              {"capabilities", Json::array()},
              {"supportedEncodings", Json::array()},
              {"metadata", Json::object()},
              {"sessionId", session_id}}
      .dump();
}

std::string advertiseJson(const std::vector<Channel>& channels) {
  Json list = Json::array();
  for (const Channel& c : channels) {
    list.push_back({{"id", c.id},
                    {"topic", c.topic},
                    {"encoding", "json"},
                    {"schemaName", c.schema_name},
                    {"schema", c.schema},
                    {"schemaEncoding", "jsonschema"}});
  }
  return Json{{"op", "advertise"}, {"channels", list}}.dump();
}

std::string statusJson(int level, const std::string& message) {
  return Json{{"op", "status"}, {"level", level}, {"message", message}}.dump();
}

std::vector<std::uint8_t> messageDataFrame(std::uint32_t subscription_id, std::uint64_t timestamp_ns,
                                           std::string_view payload) {
  std::vector<std::uint8_t> frame;
  frame.reserve(13 + payload.size());
  frame.push_back(0x01);
  for (int i = 0; i < 4; ++i) frame.push_back(static_cast<std::uint8_t>(subscription_id >> (8 * i)));
  for (int i = 0; i < 8; ++i) frame.push_back(static_cast<std::uint8_t>(timestamp_ns >> (8 * i)));
  frame.insert(frame.end(), payload.begin(), payload.end());
  return frame;
}

ClientRequest parseClientRequest(std::string_view text) {
  const Json j = Json::parse(text, nullptr, false);
  if (j.is_discarded() || !j.is_object()) return Unsupported{"not a JSON object"};
  const auto op = j.find("op");
  if (op == j.end() || !op->is_string()) return Unsupported{"no op"};
  const auto u32 = [](const Json& v) -> std::optional<std::uint32_t> {
    if (!v.is_number_unsigned() || v.get<std::uint64_t>() > 0xFFFFFFFFull) return std::nullopt;
    return static_cast<std::uint32_t>(v.get<std::uint64_t>());
  };
  if (*op == "subscribe") {
    const auto list = j.find("subscriptions");
    if (list == j.end() || !list->is_array()) return Unsupported{"subscribe without subscriptions"};
    Subscribe s;
    for (const Json& e : *list) {
      if (!e.is_object() || !e.contains("id") || !e.contains("channelId")) return Unsupported{"malformed subscription"};
      const auto id = u32(e["id"]);
      const auto channel = u32(e["channelId"]);
      if (!id || !channel) return Unsupported{"malformed subscription"};
      s.subscriptions.emplace_back(*id, *channel);
    }
    return s;
  }
  if (*op == "unsubscribe") {
    const auto list = j.find("subscriptionIds");
    if (list == j.end() || !list->is_array()) return Unsupported{"unsubscribe without subscriptionIds"};
    Unsubscribe u;
    for (const Json& e : *list) {
      const auto id = u32(e);
      if (!id) return Unsupported{"malformed subscription id"};
      u.subscription_ids.push_back(*id);
    }
    return u;
  }
  return Unsupported{"op " + op->get<std::string>() + " is not supported by this server"};
}

}  // namespace swa::live

#pragma once
// The Foxglove WebSocket protocol v1 (github.com/foxglove/ws-protocol, docs/spec.md), the server side of what the
// live view needs: the server's text messages, the binary message-data frame, and the client's subscribe and
// unsubscribe requests. What Foxglove, Lichtblick and the @foxglove/ws-protocol client speak. No I/O.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

namespace swa::live {

// The WebSocket subprotocols a client may ask for; both name protocol v1 (the second is what the Foxglove SDK's
// clients ask for).
constexpr const char* kSubprotocols[] = {"foxglove.websocket.v1", "foxglove.sdk.v1"};
// The first of `requested` (in the client's order) that the server speaks; nullopt: none.
std::optional<std::string> selectSubprotocol(const std::vector<std::string>& requested);

struct Channel {
  std::uint32_t id = 0;
  std::string topic;
  std::string schema_name;
  std::string schema;  // a JSON Schema, as text; messages are JSON
};

std::string serverInfoJson(const std::string& name, const std::string& session_id);
std::string advertiseJson(const std::vector<Channel>& channels);
// A status message (level 0 info, 1 warning, 2 error), e.g. for a request the server did not understand.
std::string statusJson(int level, const std::string& message);

// Binary frame "message data": opcode 0x01, subscription id (u32 LE), timestamp in ns (u64 LE), payload.
std::vector<std::uint8_t> messageDataFrame(std::uint32_t subscription_id, std::uint64_t timestamp_ns,
                                           std::string_view payload);

struct Subscribe {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> subscriptions;  // (subscription id, channel id)
};
struct Unsubscribe {
  std::vector<std::uint32_t> subscription_ids;
};
struct Unsupported {
  std::string why;  // for a status message back (malformed JSON, an op this server does not implement)
};
using ClientRequest = std::variant<Subscribe, Unsubscribe, Unsupported>;

// A text message of a client.
ClientRequest parseClientRequest(std::string_view text);

}  // namespace swa::live

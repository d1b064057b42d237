#pragma once
// The live view's server (swa_monitor --live): one TCP port that answers HTTP GET "/" with the self-contained live
// page and upgrades WebSocket connections that ask for the Foxglove protocol (foxglove_protocol.h), so a browser,
// Foxglove or Lichtblick watch the swarm while it flies. Built on websocketpp with standalone asio (Debian packages),
// on a thread of its own: publish() never blocks the monitor, and a client that cannot keep up loses messages
// (counted) instead of growing the monitor's memory. Bound to 127.0.0.1 unless told otherwise: other hosts cannot
// connect at all by default.

#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>

namespace swa::live {

class LiveError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class LiveServer {
 public:
  struct Options {
    std::string address = "127.0.0.1";  // to listen on; another (0.0.0.0) lets other hosts connect
    int port = 8765;                    // 0: any free port (port() says which)
    std::string name = "swa_monitor";   // serverInfo's name
    std::string page;                   // the HTML served at "/"
    // Per client: bytes queued for sending above which new messages are dropped for that client.
    std::size_t max_buffered_bytes = 4u << 20;
  };
  struct Stats {
    std::uint64_t connections = 0;  // WebSocket clients accepted so far
    int connected = 0;              // ... connected now
    std::uint64_t refused = 0;      // WebSocket handshakes refused (no Foxglove subprotocol, not local)
    std::uint64_t pages = 0;        // HTTP page requests answered
    std::uint64_t sent = 0;         // messages sent to subscribers
    std::uint64_t dropped = 0;      // messages not sent to a client that could not keep up
  };

  // Listens and starts serving. Throws LiveError (address not usable, port taken).
  explicit LiveServer(const Options& options);
  // Closes every connection ("going away") and stops.
  ~LiveServer();
  LiveServer(const LiveServer&) = delete;
  LiveServer& operator=(const LiveServer&) = delete;

  int port() const;
  // A channel of JSON messages with this JSON Schema; advertised to every client, now and later. Thread-safe.
  std::uint32_t addChannel(const std::string& topic, const std::string& schema_name, const std::string& schema);
  // Sends `json` on `channel` to every client subscribed to it. Thread-safe, does not wait.
  void publish(std::uint32_t channel, std::uint64_t timestamp_ns, std::string json);
  Stats stats() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace swa::live

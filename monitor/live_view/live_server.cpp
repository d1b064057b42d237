#include "live_server.h"

// websocketpp on standalone asio, with the C++11 standard library in place of Boost.
#define ASIO_STANDALONE
#define _WEBSOCKETPP_CPP11_STL_
#include <websocketpp/config/asio_no_tls.hpp>
#include <websocketpp/server.hpp>

#include <atomic>
#include <chrono>
#include <map>
#include <mutex>
#include <thread>
#include <vector>

#include "foxglove_protocol.h"

namespace swa::live {
namespace {

using WsServer = websocketpp::server<websocketpp::config::asio>;
using Handle = websocketpp::connection_hdl;

// Messages waiting for the server's thread above which publish() drops (the thread is stuck or starved): the monitor's
// memory stays bounded whatever happens to the clients.
constexpr int kMaxPending = 10'000;

std::string sessionId() { return std::to_string(std::chrono::system_clock::now().time_since_epoch().count()); }

}  // namespace

struct LiveServer::Impl {
  Options options;
  WsServer server;
  std::thread thread;
  bool allow_remote = false;
  std::atomic<int> pending{0};

  mutable std::mutex mutex;  // channels and stats; the connections are touched on the server's thread only
  std::vector<Channel> channels;
  Stats stats;
  const std::string session = sessionId();

  struct Client {
    std::map<std::uint32_t, std::uint32_t> subscriptions;  // subscription id -> channel id
  };
  std::map<Handle, Client, std::owner_less<Handle>> clients;

  bool local(WsServer::connection_ptr con) {
    asio::error_code ec;
    const auto remote = con->get_raw_socket().remote_endpoint(ec);
    if (ec) return false;
    const asio::ip::address a = remote.address();
    if (a.is_loopback()) return true;
    return a.is_v6() && a.to_v6().is_v4_mapped() &&
           asio::ip::make_address_v4(asio::ip::v4_mapped, a.to_v6()).is_loopback();
  }

  void sendText(Handle h, const std::string& text) {
    asio::error_code ec;
    server.send(h, text, websocketpp::frame::opcode::text, ec);
  }

  void onHttp(Handle h) {
    WsServer::connection_ptr con = server.get_con_from_hdl(h);
    if (!allow_remote && !local(con)) {
      con->set_status(websocketpp::http::status_code::forbidden);
      return;
    }
    const std::string resource = con->get_resource();
    if (resource == "/" || resource == "/index.html") {
      con->set_status(websocketpp::http::status_code::ok);
      con->append_header("Content-Type", "text/html; charset=utf-8");
      con->append_header("Cache-Control", "no-store");
      con->set_body(options.page);
      const std::lock_guard<std::mutex> lock(mutex);
      ++stats.pages;
    } else {
      con->set_status(websocketpp::http::status_code::not_found);
      con->append_header("Content-Type", "text/plain");
      con->set_body("not found: the live view is at /\n");
    }
  }

  bool onValidate(Handle h) {
    WsServer::connection_ptr con = server.get_con_from_hdl(h);
    const std::optional<std::string> protocol = selectSubprotocol(con->get_requested_subprotocols());
    if (!protocol || (!allow_remote && !local(con))) {
      const std::lock_guard<std::mutex> lock(mutex);
      ++stats.refused;
      return false;
    }
    con->select_subprotocol(*protocol);
    return true;
  }

  void onOpen(Handle h) {
    clients[h] = Client{};
    std::vector<Channel> now;
    {
      const std::lock_guard<std::mutex> lock(mutex);
      ++stats.connections;
      stats.connected = static_cast<int>(clients.size());
      now = channels;
    }
    sendText(h, serverInfoJson(options.name, session));
    if (!now.empty()) sendText(h, advertiseJson(now));
  }

  void onClose(Handle h) {
    clients.erase(h);
    const std::lock_guard<std::mutex> lock(mutex);
    stats.connected = static_cast<int>(clients.size());
  }

  void onMessage(Handle h, WsServer::message_ptr msg) {
    auto client = clients.find(h);
    if (client == clients.end()) return;
    if (msg->get_opcode() != websocketpp::frame::opcode::text) {
      sendText(h, statusJson(1, "binary client messages are not supported by this server"));
      return;
    }
    const ClientRequest request = parseClientRequest(msg->get_payload());
    if (const auto* s = std::get_if<Subscribe>(&request)) {
      for (const auto& [id, channel] : s->subscriptions) client->second.subscriptions[id] = channel;
    } else if (const auto* u = std::get_if<Unsubscribe>(&request)) {
      for (const std::uint32_t id : u->subscription_ids) client->second.subscriptions.erase(id);
    } else {
      sendText(h, statusJson(1, std::get<Unsupported>(request).why));
    }
  }

  // On the server's thread.
  void deliver(std::uint32_t channel, std::uint64_t timestamp_ns, const std::string& json) {
    std::uint64_t sent = 0, dropped = 0;
    for (auto& [h, client] : clients) {
      for (const auto& [id, subscribed] : client.subscriptions) {
        if (subscribed != channel) continue;
        asio::error_code ec;
        WsServer::connection_ptr con = server.get_con_from_hdl(h, ec);
        if (ec || con->get_buffered_amount() > options.max_buffered_bytes) {
          ++dropped;
          continue;
        }
        const std::vector<std::uint8_t> frame = messageDataFrame(id, timestamp_ns, json);
        con->send(frame.data(), frame.size(), websocketpp::frame::opcode::binary);
        ++sent;
      }
    }
    const std::lock_guard<std::mutex> lock(mutex);
    stats.sent += sent;
    stats.dropped += dropped;
  }
};

LiveServer::LiveServer(const Options& options) : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.options = options;
  WsServer& s = m.server;
  s.clear_access_channels(websocketpp::log::alevel::all);
  s.clear_error_channels(websocketpp::log::elevel::all);
  asio::error_code ec;
  const asio::ip::address address = asio::ip::make_address(options.address, ec);
  if (ec) throw LiveError("--live: '" + options.address + "' is not an IP address");
  m.allow_remote = !address.is_loopback();
  s.init_asio();
  s.set_reuse_addr(true);
  s.set_http_handler([&m](Handle h) { m.onHttp(h); });
  s.set_validate_handler([&m](Handle h) { return m.onValidate(h); });
  s.set_open_handler([&m](Handle h) { m.onOpen(h); });
  s.set_close_handler([&m](Handle h) { m.onClose(h); });
  s.set_fail_handler([](Handle) {});
  s.set_message_handler([&m](Handle h, WsServer::message_ptr msg) { m.onMessage(h, msg); });
  s.listen(asio::ip::tcp::endpoint(address, static_cast<unsigned short>(options.port)), ec);
  if (ec) {
    throw LiveError("--live: cannot listen on " + options.address + ":" + std::to_string(options.port) + ": " +
                    ec.message());
  }
  s.start_accept(ec);
  if (ec) throw LiveError("--live: cannot accept connections: " + ec.message());
  m.thread = std::thread([&s] { s.run(); });
}

LiveServer::~LiveServer() {
  Impl& m = *impl_;
  asio::post(m.server.get_io_service(), [&m] {
    asio::error_code ec;
    m.server.stop_listening(ec);
    for (auto& [h, client] : m.clients) m.server.close(h, websocketpp::close::status::going_away, "run ended", ec);
  });
  // The closing handshakes take a round trip; then the loop is stopped whatever is left.
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  m.server.stop();
  if (m.thread.joinable()) m.thread.join();
}

int LiveServer::port() const {
  asio::error_code ec;
  const auto endpoint = impl_->server.get_local_endpoint(ec);
  return ec ? -1 : endpoint.port();
}

std::uint32_t LiveServer::addChannel(const std::string& topic, const std::string& schema_name,
                                     const std::string& schema) {
  Impl& m = *impl_;
  Channel channel;
  {
    const std::lock_guard<std::mutex> lock(m.mutex);
    channel = {static_cast<std::uint32_t>(m.channels.size() + 1), topic, schema_name, schema};
    m.channels.push_back(channel);
  }
  asio::post(m.server.get_io_service(), [&m, channel] {
    const std::string advertise = advertiseJson({channel});
    for (auto& [h, client] : m.clients) m.sendText(h, advertise);
  });
  return channel.id;
}

void LiveServer::publish(std::uint32_t channel, std::uint64_t timestamp_ns, std::string json) {
  Impl& m = *impl_;
  if (m.pending.fetch_add(1) >= kMaxPending) {
    --m.pending;
    const std::lock_guard<std::mutex> lock(m.mutex);
    ++m.stats.dropped;
    return;
  }
  asio::post(m.server.get_io_service(), [&m, channel, timestamp_ns, json = std::move(json)] {
    --m.pending;
    m.deliver(channel, timestamp_ns, json);
  });
}

LiveServer::Stats LiveServer::stats() const {
  const std::lock_guard<std::mutex> lock(impl_->mutex);
  return impl_->stats;
}

}  // namespace swa::live

#include "swa/app/udp_port.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>

namespace swa::app {

bool udpPortInUse(int port) {
  const int fd = ::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  if (fd < 0) return false;
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(static_cast<std::uint16_t>(port));
  address.sin_addr.s_addr = htonl(INADDR_ANY);
  const bool in_use =
      ::bind(fd, reinterpret_cast<const sockaddr*>(&address), sizeof address) != 0 && errno == EADDRINUSE;
  ::close(fd);
  return in_use;
}

std::optional<int> firstFreeUdpPort(int first, int count) {
  for (int port = first; port < first + count && port <= 65535; ++port) {
    if (!udpPortInUse(port)) return port;
  }
  return std::nullopt;
}

}  // namespace swa::app

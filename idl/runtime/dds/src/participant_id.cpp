#include "swa/dds/participant_id.h"

#include <algorithm>

namespace swa::dds {

std::pair<int, int> unicastPorts(int domain, const PortMapping& ports, int id) {
  const int first = ports.base + ports.domain_gain * domain + ports.participant_gain * id;
  return {first + ports.meta_unicast_offset, first + ports.user_unicast_offset};
}

std::optional<int> unusedParticipantId(int domain, const PortMapping& ports, const std::function<bool(int)>& exists) {
  const int next_domain = ports.base + ports.domain_gain * (domain + 1);
  const int next_multicast[] = {next_domain + ports.meta_multicast_offset, next_domain + ports.user_multicast_offset};
  const auto isNextMulticast = [&](int port) { return port == next_multicast[0] || port == next_multicast[1]; };
  for (int id = 0;; ++id) {
    const auto [meta, user] = unicastPorts(domain, ports, id);
    if (std::max(meta, user) >= next_domain + ports.domain_gain || std::max(meta, user) > 65535) break;
    if (isNextMulticast(meta) || isNextMulticast(user)) continue;
    if (!exists(meta) && !exists(user)) return id;
  }
  return std::nullopt;
}

}  // namespace swa::dds

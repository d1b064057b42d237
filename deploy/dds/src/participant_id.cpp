#include "swa/dds/participant_id.h"

namespace swa::dds {

std::pair<int, int> unicastPorts(int domain, const PortMapping& ports, int id) {
  const int first = ports.base + ports.domain_gain * domain + ports.participant_gain * id;
  return {first + ports.meta_unicast_offset, first + ports.user_unicast_offset};
}

std::optional<int> unusedParticipantId(int domain, const PortMapping& ports, const std::function<bool(int)>& exists) {
  const int first = ports.base + ports.domain_gain * domain;
  for (int id = 0; id < kMaxParticipantId; ++id) {
    const auto [meta, user] = unicastPorts(domain, ports, id);
    if (user - first >= ports.domain_gain) break;
    if (!exists(meta) && !exists(user)) return id;
  }
  return std::nullopt;
}

}  // namespace swa::dds

#include "swa/dds/participant_id.h"

namespace swa::dds {

std::optional<int> unusedParticipantId(int domain, const PortMapping& ports, const std::function<bool(int)>& exists) {
  const int first = ports.base + ports.domain_gain * domain;
  for (int id = 0; id < kMaxParticipantId; ++id) {
    const int meta = first + ports.meta_unicast_offset + ports.participant_gain * id;
    const int user = first + ports.user_unicast_offset + ports.participant_gain * id;
    if (user - first >= ports.domain_gain) break;
    if (!exists(meta) && !exists(user)) return id;
  }
  return std::nullopt;
}

}  // namespace swa::dds

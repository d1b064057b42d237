#pragma once
// Which DDS participant id a new SWA participant takes on this host.
//
// Fast DDS 2.9 gives a new participant the lowest id whose ports are free. After a process was killed, that is the
// dead process's id, and its shared-memory port (/dev/shm/fastrtps_port<N>) is still there: the new process finds it
// abandoned, deletes it and creates a fresh one under the same name. Every process that had sent to the dead one
// still holds the deleted port mapped and keeps writing into it; it notices only once that port fills up (Fast DDS
// fixed this after 2.9). A simulator's 100 Hz IMU fills it within seconds, but discovery traffic never does: a
// restarted agent then never matches the simulator, or the monitor never matches the agent, for the rest of the run
// (measured: 1 to 2 of the 11 restarts of the chaos test). So a participant takes the lowest id whose shared-memory
// ports were never created, or were removed when their owner closed them: no port a peer may still hold is reused.
//
// Pure: the caller says which ports exist.

#include <functional>
#include <optional>
#include <utility>

namespace swa::dds {

// Fast DDS's port mapping (DDSI-RTPS 9.6.1.1): PB + DG * domain + d1 (metatraffic) or d3 (user) + PG * id.
struct PortMapping {
  int base = 7400, domain_gain = 250, participant_gain = 2, meta_unicast_offset = 10, user_unicast_offset = 11;
};

// Ids stay below this so that a participant's ports stay inside its domain's range of DG ports.
constexpr int kMaxParticipantId = 120;

// The metatraffic and user unicast ports of participant `id` on `domain`.
std::pair<int, int> unicastPorts(int domain, const PortMapping& ports, int id);

// The lowest participant id in [0, kMaxParticipantId) of which neither unicast port exists, if there is one.
std::optional<int> unusedParticipantId(int domain, const PortMapping& ports, const std::function<bool(int)>& exists);

}  // namespace swa::dds

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

// Fast DDS's port mapping (DDSI-RTPS 9.6.1.1): PB + DG * domain + d0 (discovery multicast), d2 (user multicast),
// d1 (metatraffic unicast) or d3 (user unicast) + PG * id.
struct PortMapping {
  int base = 7400, domain_gain = 250, participant_gain = 2, meta_multicast_offset = 0, user_multicast_offset = 1,
      meta_unicast_offset = 10, user_unicast_offset = 11;
};

// The metatraffic and user unicast ports of participant `id` on `domain`.
std::pair<int, int> unicastPorts(int domain, const PortMapping& ports, int id);

// The lowest participant id of which neither unicast port exists, if there is one. A domain's range of DG ports holds
// 120 participants; more (a swarm of 100+ processes on one host) take ports of the next domain's range: those are
// free unless that domain is in use on this host (then they exist and are skipped), except the next domain's two
// multicast ports, which are never taken. No id reaches the range of the domain after next or past port 65535.
// Fast DDS 2.9 alone gives up after 100 ids (its builtin mutation_tries): the 102nd participant on a host gets no
// unicast port at all.
std::optional<int> unusedParticipantId(int domain, const PortMapping& ports, const std::function<bool(int)>& exists);

}  // namespace swa::dds

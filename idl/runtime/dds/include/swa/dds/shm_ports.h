#pragma once
// Whether a process still hears its own shared-memory ports.
//
// Fast DDS 2.9 judges a shared-memory port whose listener has not checked in for 1 s dead (healthy_check_timeout_ms);
// a sender then deletes /dev/shm/fastrtps_port<N> and creates a fresh one under that name. Normally the owner moves
// to the new one; in a race it keeps listening on the deleted one, and everyone who opens the port from then on
// writes where it no longer reads (seen here: after the 4th 2 s SIGSTOP of a realtime simulator, no command of its
// six agents reached it again). The sign, in /proc/self/maps: an own port mapped only as "(deleted)" while a file of
// that name exists. A port is a process's own when it holds the lock of its exclusive-read lock file
// (/dev/shm/fastrtps_port<N>_el, a FLOCK in /proc/locks): the participant id and so the port number Fast DDS ends up
// with can differ from the one asked for (two processes starting together), the ports a process writes to are mapped
// in it too, and a child can inherit its parent's lock file descriptors (Fast DDS opens them without O_CLOEXEC).
// The parsers are pure: the caller passes the texts of /proc files and says which ports exist. The last two apply
// them to this process (Participant::ownSharedMemoryPorts / deafSharedMemoryPorts forward to them).

#include <functional>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace swa::dds {

// The port of an exclusive-read lock file's path (/dev/shm/fastrtps_port<N>_el), if it is one.
std::optional<int> lockFilePort(const std::string& path);

// The inodes on which `pid` holds a granted lock, from the text of /proc/locks (waiters, "->", excluded).
std::set<unsigned long> lockedInodes(const std::string& proc_locks, long pid);

// The ports of `own` that `maps` (the text of /proc/<pid>/maps) shows mapped, every mapping of them deleted, and of
// which a file exists again (`exists`), in the order of `own`.
std::vector<int> deafPorts(const std::string& maps, const std::vector<int>& own,
                           const std::function<bool(int)>& exists);

// The shared-memory ports this process listens on as their only reader, sorted (its /proc/locks, /proc/self/fd).
std::vector<int> ownSharedMemoryPorts();
// Those of them that Fast DDS re-created under it (its /proc/self/maps, /dev/shm).
std::vector<int> deafSharedMemoryPorts();
// The same among `own`, found once per participant: finding them takes about 0.2 ms here, a look among them 0.05.
std::vector<int> deafSharedMemoryPorts(const std::vector<int>& own);

}  // namespace swa::dds

#pragma once
// A process's own shared-memory ports, for the tests that re-create them under it (issue #46: a process that keeps
// listening on a port a peer deleted and created again hears nothing more; swa/dds/deaf_port_watch.h). They plant
// files in /dev/shm, so they run in a /dev/shm of their own (private_shm.h).

#include <sys/types.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <system_error>
#include <vector>

namespace swa::testing {

// Whether process `pid` has `file` open.
inline bool holdsOpen(pid_t pid, const std::string& file) {
  std::error_code ec;
  for (std::filesystem::directory_iterator it("/proc/" + std::to_string(pid) + "/fd", ec), end; !ec && it != end;
       it.increment(ec)) {
    std::error_code link_ec;
    if (std::filesystem::read_symlink(it->path(), link_ec).string() == file && !link_ec) return true;
  }
  return false;
}

// The ports `who` says it listens on when it connects ("<who>: listening on shared-memory ports 7411 7412"): those
// whose exclusive-read lock it holds (in a run here the simulator had asked for agent 0's participant id and Fast DDS
// gave it the next free ports, so they cannot be computed from the id asked for). The first such line of `log`.
inline std::set<int> listedPorts(const std::string& log, const std::string& who) {
  std::smatch m;
  std::set<int> ports;
  if (!std::regex_search(log, m, std::regex(who + ": listening on shared-memory ports ([0-9 ]+)\n"))) return ports;
  std::istringstream listed(m[1].str());
  for (int port = 0; listed >> port;) ports.insert(port);
  return ports;
}

inline std::string lockFileOf(int port) { return "/dev/shm/fastrtps_port" + std::to_string(port) + "_el"; }

// Deletes the ports' files and creates files of the same names again, as a sender that judged them dead would. The
// files made, for the test to remove at its end.
inline std::vector<std::filesystem::path> recreatePortFiles(const std::set<int>& ports) {
  std::vector<std::filesystem::path> made;
  for (const int port : ports) {
    const std::filesystem::path file = "/dev/shm/fastrtps_port" + std::to_string(port);
    std::error_code ec;
    std::filesystem::remove(file, ec);
    std::ofstream(file) << "re-created";
    made.push_back(file);
  }
  return made;
}

inline void removeFiles(const std::vector<std::filesystem::path>& files) {
  for (const std::filesystem::path& file : files) {
    std::error_code ec;
    std::filesystem::remove(file, ec);
  }
}

// The port the first "deaf on shared-memory port <N>" of `log` names, or -1.
inline int deafPortNamed(const std::string& log) {
  static const std::string kSaid = "deaf on shared-memory port ";
  const std::size_t at = log.find(kSaid);
  if (at == std::string::npos) return -1;
  return std::atoi(log.c_str() + at + kSaid.size());
}

}  // namespace swa::testing

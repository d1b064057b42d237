#include "swa/dds/shm_ports.h"

#include <map>
#include <sstream>

namespace swa::dds {

std::vector<int> deafPorts(const std::string& maps, const std::vector<int>& own,
                           const std::function<bool(int)>& exists) {
  struct Seen {
    bool deleted = false, live = false;
  };
  std::map<int, Seen> seen;
  static const std::string kPrefix = "/dev/shm/fastrtps_port";
  std::istringstream lines(maps);
  std::string line;
  while (std::getline(lines, line)) {
    const std::size_t at = line.find(kPrefix);
    if (at == std::string::npos) continue;
    std::size_t end = at + kPrefix.size();
    int port = 0;
    bool digits = false;
    while (end < line.size() && line[end] >= '0' && line[end] <= '9' && port < 1'000'000) {
      port = port * 10 + (line[end++] - '0');
      digits = true;
    }
    // fastrtps_port<N>_el and the like are other files (the port's mutex, its lock): only the segment itself counts.
    if (!digits || (end < line.size() && line[end] != ' ')) continue;
    Seen& s = seen[port];
    (line.compare(end, std::string::npos, " (deleted)") == 0 ? s.deleted : s.live) = true;
  }
  std::vector<int> deaf;
  for (const int port : own) {
    const auto it = seen.find(port);
    if (it != seen.end() && it->second.deleted && !it->second.live && exists(port)) deaf.push_back(port);
  }
  return deaf;
}

}  // namespace swa::dds

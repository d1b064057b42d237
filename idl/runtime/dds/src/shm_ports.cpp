#include "swa/dds/shm_ports.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <system_error>

#include <sys/stat.h>
#include <unistd.h>

namespace swa::dds {

namespace {

std::string readWhole(const char* path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace

std::optional<int> lockFilePort(const std::string& path) {
  static const std::string kPrefix = "/dev/shm/fastrtps_port";
  static const std::string kSuffix = "_el";
  if (path.size() <= kPrefix.size() + kSuffix.size() || path.compare(0, kPrefix.size(), kPrefix) != 0 ||
      path.compare(path.size() - kSuffix.size(), kSuffix.size(), kSuffix) != 0) {
    return std::nullopt;
  }
  const std::string digits = path.substr(kPrefix.size(), path.size() - kPrefix.size() - kSuffix.size());
  if (digits.empty() || digits.size() > 6 || digits.find_first_not_of("0123456789") != std::string::npos) {
    return std::nullopt;
  }
  return std::stoi(digits);
}

std::set<unsigned long> lockedInodes(const std::string& proc_locks, long pid) {
  // "1: FLOCK  ADVISORY  WRITE 22855 00:1b:229995 0 EOF": number, class, kind, mode, pid, major:minor:inode, range
  std::set<unsigned long> inodes;
  std::istringstream lines(proc_locks);
  std::string line;
  while (std::getline(lines, line)) {
    if (line.find("->") != std::string::npos) continue;
    std::istringstream fields(line);
    std::string number, lock_class, kind, mode, device;
    long holder = 0;
    if (!(fields >> number >> lock_class >> kind >> mode >> holder >> device) || holder != pid) continue;
    const std::size_t colon = device.rfind(':');
    if (colon == std::string::npos || colon + 1 >= device.size()) continue;
    const std::string inode = device.substr(colon + 1);
    if (inode.find_first_not_of("0123456789") != std::string::npos || inode.size() > 19) continue;
    inodes.insert(std::stoul(inode));
  }
  return inodes;
}

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

std::vector<int> ownSharedMemoryPorts() {
  const std::set<unsigned long> locked = lockedInodes(readWhole("/proc/locks"), static_cast<long>(::getpid()));
  std::vector<int> own;
  std::error_code ec;
  for (std::filesystem::directory_iterator it("/proc/self/fd", ec), end; !ec && it != end; it.increment(ec)) {
    std::error_code link_ec;
    const std::optional<int> port = lockFilePort(std::filesystem::read_symlink(it->path(), link_ec).string());
    struct stat st {};
    if (link_ec || !port || ::stat(it->path().c_str(), &st) != 0) continue;
    if (locked.count(static_cast<unsigned long>(st.st_ino)) > 0) own.push_back(*port);
  }
  std::sort(own.begin(), own.end());
  own.erase(std::unique(own.begin(), own.end()), own.end());
  return own;
}

std::vector<int> deafSharedMemoryPorts() { return deafSharedMemoryPorts(ownSharedMemoryPorts()); }

std::vector<int> deafSharedMemoryPorts(const std::vector<int>& own) {
  if (own.empty()) return {};
  return deafPorts(readWhole("/proc/self/maps"), own, [](int port) {
    std::error_code ec;
    return std::filesystem::exists("/dev/shm/fastrtps_port" + std::to_string(port), ec);
  });
}

}  // namespace swa::dds

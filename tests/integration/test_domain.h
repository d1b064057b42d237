#pragma once
// DDS domains reserved among SWA's tests on this host.

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <string>
#include <vector>

namespace swa::testing {

// Reserves DDS domain `first`, or the next one (1..232, wrapping) that no other SWA test holds, for the rest of this
// process: an exclusive flock on /tmp/swa-test-domain-<d>.lock, released by the kernel when the process ends, and
// shared with the scripted tests (tests/script_tools.sh). Tests run two at a time (ctest -j2) and some of them look at
// a whole domain (the isolation audit's observer, processesOnDomain), so two of them must never share one; the
// swarm partition (useOwnSwarm) only keeps their samples apart. Returns -1 when all 232 are taken.
inline int reserveTestDomain(int first) {
  static std::vector<int> held;  // the lock files' descriptors, open until exit
  for (int k = 0; k < 232; ++k) {
    const int domain = 1 + (first - 1 + k) % 232;
    const std::string path = "/tmp/swa-test-domain-" + std::to_string(domain) + ".lock";
    const int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0666);
    if (fd < 0) continue;
    if (::flock(fd, LOCK_EX | LOCK_NB) == 0) {
      held.push_back(fd);
      return domain;
    }
    ::close(fd);
  }
  return -1;
}

}  // namespace swa::testing

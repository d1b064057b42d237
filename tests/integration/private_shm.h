#pragma once
// A /dev/shm of the test's own, for every test that checks it left no shared-memory file behind, and every test that
// kills a process with SIGKILL.
//
// Fast DDS 2.9 leaves a killed process's shared-memory segments in /dev/shm until the last peer that mapped them
// closes them, and names them fastrtps_<random id>: nothing in the name says whose they are. A test running beside
// a killer (ctest -j2, or another DDS user of the host) that checks it left no abandoned file behind would count the
// killer's as its own: LaunchTest.UnwritableOutputStartsNothingAndExits2 did once in CI, with the chaos test (which
// SIGKILLs agents) running beside it. With a tmpfs of its own on /dev/shm, nobody else's files are there to see, its
// own are nobody else's, and the kernel frees them all when the test's last process ends.

#include <sched.h>
#include <sys/mount.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <string>

namespace swa::testing {

namespace detail {

inline std::string makePrivateShm() {
  const auto failed = [](const char* what) { return std::string(what) + ": " + std::strerror(errno); };
  if (::unshare(CLONE_NEWNS) != 0) return failed("unshare(CLONE_NEWNS) (a /dev/shm of the test's own needs root)");
  // Mounts made from here on stay in this namespace (systemd makes / shared, which would propagate them back).
  if (::mount(nullptr, "/", nullptr, MS_REC | MS_PRIVATE, nullptr) != 0) return failed("making / private");
  if (::mount("swa-test-shm", "/dev/shm", "tmpfs", MS_NOSUID | MS_NODEV, "mode=1777,size=1g") != 0) {
    return failed("mounting a tmpfs on /dev/shm");
  }
  return "";
}

}  // namespace detail

// Moves the calling thread into a new mount namespace with a fresh tmpfs on /dev/shm; every process and thread it
// starts from then on (the Fast DDS participants the test makes, the programs it launches) shares it, nothing outside
// sees it. Once per process: Fast DDS's shared-memory watchdog is one thread per process, started with the first
// participant, and it must look at the same /dev/shm as every participant after it, so a second namespace (the next
// test of a binary run by hand) would make it check port files it cannot see. Needs root (CAP_SYS_ADMIN), like the
// network-namespace and loss tests. Returns "" when done, else why not.
inline std::string usePrivateShm() {
  static const std::string why_not = detail::makePrivateShm();
  return why_not;
}

// A fixture's first member: the test's own /dev/shm before anything of the test (its janitor, its participants, the
// programs it starts) touches /dev/shm. Throws, which fails the test naming the reason, when it cannot be had.
struct OwnShm {
  OwnShm() {
    const std::string why_not = usePrivateShm();
    if (!why_not.empty()) throw std::runtime_error("this test needs a /dev/shm of its own: " + why_not);
  }
};

}  // namespace swa::testing

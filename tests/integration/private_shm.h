#pragma once
// A /dev/shm of the test's own, for a test that kills a process with SIGKILL.
//
// Fast DDS 2.9 leaves a killed process's shared-memory segments in /dev/shm until the last peer that mapped them
// closes them, and names them fastrtps_<random id>: nothing in the name says whose they are. A test running beside
// a killer (ctest -j2) that checks it left no abandoned file behind would count the killer's as its own. With a
// tmpfs of its own on /dev/shm, the killer's files are nobody else's to see, and the kernel frees them all when the
// test's last process ends.

#include <sched.h>
#include <sys/mount.h>

#include <cerrno>
#include <cstring>
#include <string>

namespace swa::testing {

// Moves the calling thread into a new mount namespace with a fresh tmpfs on /dev/shm; every process and thread it
// starts from now on (the Fast DDS participants the test makes, the programs it launches) shares it, nothing outside
// sees it. Call it first in the test, before anything of the test touches /dev/shm. Needs root (CAP_SYS_ADMIN), like
// the network-namespace and loss tests. Returns "" when done, else why not.
inline std::string usePrivateShm() {
  const auto failed = [](const char* what) { return std::string(what) + ": " + std::strerror(errno); };
  if (::unshare(CLONE_NEWNS) != 0) return failed("unshare(CLONE_NEWNS) (a /dev/shm of the test's own needs root)");
  // Mounts made from here on stay in this namespace (systemd makes / shared, which would propagate them back).
  if (::mount(nullptr, "/", nullptr, MS_REC | MS_PRIVATE, nullptr) != 0) return failed("making / private");
  if (::mount("swa-test-shm", "/dev/shm", "tmpfs", MS_NOSUID | MS_NODEV, "mode=1777,size=1g") != 0) {
    return failed("mounting a tmpfs on /dev/shm");
  }
  return "";
}

}  // namespace swa::testing

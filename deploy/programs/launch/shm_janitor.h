#pragma once
// Removes the Fast DDS shared-memory files that processes killed by a signal leave in /dev/shm, like
// `fastdds shm clean` but restricted to files that did not exist when the janitor was created, so other users' and
// other runs' files are never touched.
//
// Fast DDS keeps, per segment or port `fastrtps_X`, lock files `fastrtps_X_el` / `fastrtps_X_sl` that its live owner
// holds with flock(), and a port mutex `sem.fastrtps_X_mutex`. A process that shuts down cleanly leaves nothing; one
// killed by a signal leaves its segments, and the ports it had opened keep a reference count that never drops to
// zero (port files without lock files remain even after every other process exited cleanly). A file is abandoned
// when no live process holds a lock on its base name.

#include <filesystem>
#include <set>
#include <string>
#include <vector>

namespace swa::launch {

class ShmJanitor {
 public:
  explicit ShmJanitor(std::filesystem::path dir = "/dev/shm");

  // Abandoned files created since construction (names relative to the directory); removes them when `remove`.
  std::vector<std::string> zombies(bool remove = false) const;
  std::vector<std::string> clean() const { return zombies(true); }

 private:
  std::set<std::string> list() const;
  bool inUse(const std::string& base) const;

  std::filesystem::path dir_;
  std::set<std::string> before_;
};

}  // namespace swa::launch

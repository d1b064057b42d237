#include "shm_janitor.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <utility>

namespace swa::launch {

namespace fs = std::filesystem;

namespace {

bool endsWith(const std::string& s, const std::string& suffix) {
  return s.size() > suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

}  // namespace

ShmJanitor::ShmJanitor(fs::path dir) : dir_(std::move(dir)), before_(list()) {}

std::set<std::string> ShmJanitor::list() const {
  std::set<std::string> names;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir_, ec)) names.insert(e.path().filename().string());
  return names;
}

// A live owner holds one of the lock files (exclusively or shared): then our exclusive probe fails.
bool ShmJanitor::inUse(const std::string& base) const {
  for (const char* suffix : {"_el", "_sl"}) {
    const fs::path lock = dir_ / (base + suffix);
    const int fd = ::open(lock.c_str(), O_WRONLY | O_CLOEXEC);
    if (fd < 0) continue;
    const bool held = ::flock(fd, LOCK_EX | LOCK_NB) != 0;
    ::close(fd);
    if (held) return true;
  }
  return false;
}

std::vector<std::string> ShmJanitor::zombies(bool remove) const {
  std::set<std::string> bases;
  for (const std::string& name : list()) {
    if (before_.count(name) != 0) continue;
    std::string base = name;
    if (base.rfind("sem.", 0) == 0) base = base.substr(4);
    if (base.rfind("fastrtps_", 0) != 0) continue;
    for (const char* suffix : {"_el", "_sl", "_mutex"}) {
      if (endsWith(base, suffix)) {
        base.resize(base.size() - std::string(suffix).size());
        break;
      }
    }
    bases.insert(base);
  }
  std::vector<std::string> found;
  for (const std::string& base : bases) {
    if (inUse(base)) continue;
    for (const std::string& f : {base, base + "_el", base + "_sl", "sem." + base + "_mutex"}) {
      std::error_code ec;
      if (!fs::exists(dir_ / f, ec) || before_.count(f) != 0) continue;
      found.push_back(f);
      if (remove) fs::remove(dir_ / f, ec);
    }
  }
  return found;
}

}  // namespace swa::launch

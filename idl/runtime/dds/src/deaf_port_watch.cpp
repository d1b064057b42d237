#include "swa/dds/deaf_port_watch.h"

#include <algorithm>
#include <cstdio>
#include <utility>

#include "swa/dds/shm_ports.h"

namespace swa::dds {

DeafPortWatch::DeafPortWatch(Lookups lookups, Clock::duration period) : lookups_(std::move(lookups)), period_(period) {}

DeafPortWatch::DeafPortWatch()
    : DeafPortWatch(Lookups{[] { return ownSharedMemoryPorts(); },
                            [](const std::vector<int>& own) { return deafSharedMemoryPorts(own); }}) {}

std::optional<int> DeafPortWatch::poll(Clock::time_point now) {
  if (next_look_ && now < *next_look_) return std::nullopt;
  next_look_ = now + period_;
  if (!own_) own_ = lookups_.own();
  if (own_->empty()) return std::nullopt;  // shared memory off: nothing to hear
  for (const int port : lookups_.deaf_among(*own_)) {
    if (std::find(named_.begin(), named_.end(), port) != named_.end()) continue;
    named_.push_back(port);
    return port;
  }
  return std::nullopt;
}

void DeafPortWatch::reset() {
  own_.reset();
  named_.clear();
}

void sayOwnSharedMemoryPorts(const std::string& who) {
  const std::vector<int> ports = ownSharedMemoryPorts();
  if (ports.empty()) return;
  std::string list;
  for (const int port : ports) list += " " + std::to_string(port);
  std::fprintf(stderr, "%s: listening on shared-memory ports%s\n", who.c_str(), list.c_str());
}

std::string deafPortReason(int port, const std::string& senders) {
  const std::string n = std::to_string(port);
  return "deaf on shared-memory port " + n + ": Fast DDS re-created /dev/shm/fastrtps_port" + n +
         " under this process (a peer judged it dead, e.g. while this process was starved or stopped), so what " +
         senders + " send to it is lost";
}

}  // namespace swa::dds

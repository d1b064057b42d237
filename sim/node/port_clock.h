#pragma once
// The clock of swa_sim's drivers and ports, with its durations and wall stamps: apart so that the ports' parts
// (sensor_ports.h, world_ports.h) and the drivers (through sim_ports.h) tell time alike.

#include <chrono>

#include "swa/app/log_histogram.h"

namespace swa::sim_node {

using PortClock = std::chrono::steady_clock;

// Durations and wall stamps as the drivers and the ports use them.
inline PortClock::duration seconds(double s) {
  return std::chrono::duration_cast<PortClock::duration>(std::chrono::duration<double>(s));
}
inline double secondsSince(PortClock::time_point t0) {
  return std::chrono::duration<double>(PortClock::now() - t0).count();
}
inline app::WallNs wallNs(PortClock::time_point t) {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(t.time_since_epoch()).count();
}

}  // namespace swa::sim_node

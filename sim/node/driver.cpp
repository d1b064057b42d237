#include "driver.h"

#include <cstdio>

#include "swa/sim/timing.h"

namespace swa::sim_node {
namespace {

// A loop iteration longer than one poll plus this means the simulator itself did not run (swa/app/stall_watch.h).
// Generous: on a loaded 2-core machine a wake-up can be a few tens of milliseconds late.
constexpr auto kStallSlack = std::chrono::milliseconds(150);
// A stall this long (beyond the slack) may have outlasted the 4 s participant lease (idl/runtime/dds/profiles.xml)
// counted from the simulator's last announcement (every 1 s): the agents dropped the simulator and must find it again,
// some by re-creating their participant (agent_node.h, peer_book.h). Each then gets kReconnectGrace more for its next
// answer.
constexpr auto kLeaseLongStall = std::chrono::seconds(3);
constexpr auto kReconnectGrace = std::chrono::seconds(4);

}  // namespace

Driver::Driver(const DriverContext& context)
    : scenario_(context.scenario),
      options_(context.options),
      world_(context.world),
      ports_(context.ports),
      summary_(context.summary),
      stop_(context.stop),
      n_(context.world.uav_count()),
      stall_(kPollPeriod + kStallSlack) {}

void Driver::noteStall(Clock::duration lost, Clock::time_point now) {
  ++summary_.stalls;
  const double s = std::chrono::duration<double>(lost).count();
  summary_.stalled_s += s;
  ports_.shiftCommanders(lost, now);
  const bool lease_long = lost >= kLeaseLongStall;
  if (lease_long) reconnect_grace_until_ = now + kReconnectGrace;
  std::fprintf(stderr,
               "swa_sim: t = %.2f s: the simulator itself did not run for %.3f s: its deadlines moved by that much%s "
               "(no agent is blamed for it)\n",
               sim::stampSeconds(world_.time_ns()), s,
               lease_long ? ", and the agents get 4 s more to find it again (the stall outlasted the DDS lease)" : "");
}

}  // namespace swa::sim_node

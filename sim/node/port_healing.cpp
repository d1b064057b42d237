// SimPorts' recovery from a deaf shared-memory port (sim_ports.h): the participant re-created and every endpoint
// awaited again. Apart from sim_ports.cpp because it is a rare second start, of which the steps need know nothing.
#include "sim_ports.h"

#include <cstdio>
#include <string>
#include <thread>
#include <vector>

#include "swa/sim/timing.h"

namespace swa::sim_node {

void SimPorts::healDeafness() {
  const std::optional<int> deaf = deaf_ports_.poll(Clock::now());
  if (!deaf) return;
  const double t_s = sim::stampSeconds(world_.time_ns());
  if (autopilot_) {
    // The stand-ins' endpoints live on this participant and their vehicles' state with them: not re-created.
    std::fprintf(stderr,
                 "swa_sim: t = %.2f s: %s; with autopilot stand-ins the simulator does not re-create its participant "
                 "and the run cannot recover (deploy/README.md)\n",
                 t_s, dds::deafPortReason(*deaf, "the bridges").c_str());
    return;
  }
  ++summary_.reconnections;
  std::fprintf(stderr, "swa_sim: t = %.2f s: %s: re-creating the participant (reconnection %d)\n", t_s,
               dds::deafPortReason(*deaf, "agents").c_str(), summary_.reconnections);
  reconnect();
}

void SimPorts::reconnect() {
  const int domain_id = participant_->domainId();
  participant_->abandonAcknowledgments();  // none can reach a deaf port
  sensors_.clear();
  cmd_.clear();
  participant_.reset();
  connect(domain_id, profiles_file_);
  dds::sayOwnSharedMemoryPorts("swa_sim");
  deaf_ports_.reset();
  // What the old writers sent last may not have reached everyone before they were deleted: in lockstep, the agents
  // still waited for get the step's samples once more (repeatWhileWaiting).
  resend_after_reconnect_ = true;
  // Nothing steps until every endpoint matched again, so no answer is missed meanwhile: the drivers see the wait as
  // a stall of the simulator (swa/app/stall_watch.h) and blame no agent for it. The agents' command writers keep
  // their newest answer (TRANSIENT_LOCAL), which the new readers receive once matched.
  const auto t0 = Clock::now();
  std::vector<std::string> missing = unmatchedEndpoints();
  while (!stop_ && !missing.empty() && Clock::now() - t0 < kRematchTimeout) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    missing = unmatchedEndpoints();
  }
  if (missing.empty()) {
    std::fprintf(stderr, "swa_sim: every endpoint matched again %.2f s after re-creating the participant\n",
                 secondsSince(t0));
  } else if (!stop_) {
    std::fprintf(stderr,
                 "swa_sim: %zu endpoint(s) still unmatched %.0f s after re-creating the participant (first: "
                 "%s); the run goes on\n",
                 missing.size(), secondsSince(t0), missing.front().c_str());
  }
}

}  // namespace swa::sim_node

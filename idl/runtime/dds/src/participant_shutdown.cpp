// Participant's destructor: at most kShutdownAckWaitS for acknowledgments, then every entity, then the listeners (why:
// participant.h). Apart from creation: this order is what keeps a clean exit from hanging or leaving /dev/shm behind.
//
// The whole of it is under a Deadline (kDeletionLimitS). Fast DDS 2.9.1 can deadlock inside a secured participant
// when a remote participant leaves (1 of 50 secure launches through ArduPilot at N = 8, bench_secure_launch.sh;
// the threads' stacks taken with gdb). Three of its threads wait on each other: a receive thread removing the
// remote participant destroys its handshake timer while it holds the SecurityManager's lock, shared
// (SecurityManager::remove_participant, the same in 2.9.2), and waits for the event thread to finish a timer; the
// event thread, sending an initial ACKNACK, waits for a reader's mutex; the shared-memory receive thread holds that
// mutex and waits to take the SecurityManager's lock exclusively. The participant then neither announces itself
// (its peers drop it when its lease expires) nor can be deleted: delete_participant never returns. Only a new
// process starts clean.

#include "swa/dds/participant.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include <fastdds/dds/domain/DomainParticipantFactory.hpp>

#include "peer_listener.h"
#include "swa/dds/deadline.h"

namespace swa::dds {

namespace fdds = eprosima::fastdds::dds;

Participant::~Participant() {
  const Deadline deletion(std::chrono::duration<double>(kDeletionLimitS), [this] {
    std::fprintf(stderr,
                 "%s: deleting the participant took over %.0f s: Fast DDS is stuck inside it (seen with DDS Security "
                 "and once while re-creating a participant deaf on its shared-memory port, see deploy/README.md); "
                 "exiting with status %d for a supervisor to restart the process\n",
                 name_.c_str(), kDeletionLimitS, kExitParticipantStuck);
    std::fflush(stderr);
    std::_Exit(kExitParticipantStuck);
  });
  // See participant.h: no writer may still be heartbeating an unresponsive reader when it is deleted.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(kShutdownAckWaitS);
  for (fdds::DataWriter* w : abandon_acknowledgments_ ? std::vector<fdds::DataWriter*>() : writers_) {
    const double left = std::chrono::duration<double>(deadline - std::chrono::steady_clock::now()).count();
    if (!detail::waitForAcknowledgments(w, std::max(left, 0.0))) {
      std::fprintf(stderr, "%s: writer on %s still unacknowledged after %.0f s; deleting anyway\n", name_.c_str(),
                   w->get_topic()->get_name().c_str(), kShutdownAckWaitS);
    }
  }
  // Then every entity (readers stop calling their listeners); the listeners die after this body.
  participant_->delete_contained_entities();
  fdds::DomainParticipantFactory::get_instance()->delete_participant(participant_);
}

}  // namespace swa::dds

// Participant's destructor: at most kShutdownAckWaitS for acknowledgments, then every entity, then the listeners (why:
// participant.h). Apart from creation: this order is what keeps a clean exit from hanging or leaving /dev/shm behind.

#include "swa/dds/participant.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <vector>

#include <fastdds/dds/domain/DomainParticipantFactory.hpp>

#include "peer_listener.h"

namespace swa::dds {

namespace fdds = eprosima::fastdds::dds;

Participant::~Participant() {
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

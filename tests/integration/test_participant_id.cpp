// The participant id a new SWA participant takes (swa/dds/participant_id.h): never one whose shared-memory port a
// killed process left behind. Pure, no DDS (label unit).

#include <gtest/gtest.h>

#include <set>

#include "swa/dds/participant_id.h"

namespace swa::dds {
namespace {

TEST(ParticipantId, TakesTheLowestIdWhoseUnicastPortsWereNeverCreated) {
  // GIVEN domain 3 (ports from 7400 + 250 * 3 = 8150): ids 0 and 1 hold ports (alive or killed), id 2 only its user
  // port
  const std::set<int> ports{8160, 8161, 8162, 8163, 8165};
  const auto exists = [&](int port) { return ports.count(port) > 0; };
  // WHEN a participant chooses THEN it takes id 3: the first with neither metatraffic nor user port
  EXPECT_EQ(unusedParticipantId(3, PortMapping{}, exists), 3);
  // THEN on an empty host it takes id 0, like Fast DDS itself
  EXPECT_EQ(unusedParticipantId(3, PortMapping{}, [](int) { return false; }), 0);
}

TEST(ParticipantId, StaysInsideItsDomainsPortRangeAndGivesUpWhenItIsFull) {
  // GIVEN every port exists WHEN a participant chooses THEN there is no id (Fast DDS then picks one itself)
  EXPECT_EQ(unusedParticipantId(0, PortMapping{}, [](int) { return true; }), std::nullopt);
  // GIVEN only ports of the next domain are free WHEN choosing in domain 0 THEN none is taken: id 120 would have
  // ports 7650/7651, which belong to domain 1
  const auto own_domain_taken = [](int port) { return port < 7400 + 250; };
  EXPECT_EQ(unusedParticipantId(0, PortMapping{}, own_domain_taken), std::nullopt);
  // GIVEN a profile with another mapping WHEN choosing THEN its gains are used
  PortMapping wide;
  wide.participant_gain = 4;
  const std::set<int> taken{7410, 7411};
  EXPECT_EQ(unusedParticipantId(0, wide, [&](int port) { return taken.count(port) > 0; }), 1);
  const std::set<int> second{7414};  // id 1 under gain 4: 7414 / 7415
  EXPECT_EQ(unusedParticipantId(0, wide, [&](int port) { return second.count(port) > 0; }), 0);
}

}  // namespace
}  // namespace swa::dds

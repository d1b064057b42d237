// The participant id a new SWA participant takes (swa/dds/participant_id.h): never one whose shared-memory port a
// killed process left behind, nor one whose ports are taken, past 120 in the next domain's free ports; which UDP port
// is free (swa/app/udp_port.h); and which of its own ports a process no longer hears (swa/dds/shm_ports.h,
// deaf_port_watch.h). No DDS (label unit).

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <chrono>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "swa/app/udp_port.h"
#include "swa/dds/deaf_port_watch.h"
#include "swa/dds/participant_id.h"
#include "swa/dds/shm_ports.h"

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

TEST(ParticipantId, PastItsDomainsRangeTakesTheNextDomainsFreePortsButNeverItsMulticastPorts) {
  // GIVEN domain 0's range (7400..7649) full WHEN a participant chooses THEN it takes ports of domain 1's range:
  // not id 120 (7650 / 7651 are domain 1's discovery and user multicast ports) but id 121 (7652 / 7653)
  const auto own_domain_taken = [](int port) { return port < 7400 + 250; };
  EXPECT_EQ(unusedParticipantId(0, PortMapping{}, own_domain_taken), 121);
  // GIVEN domain 1 in use on this host (its participants 0..2 hold 7660..7665) as well THEN its ports are skipped
  const auto next_in_use = [](int port) { return port < 7400 + 250 || (port >= 7660 && port <= 7665); };
  EXPECT_EQ(unusedParticipantId(0, PortMapping{}, next_in_use), 121);
  const auto next_more_in_use = [](int port) { return port < 7400 + 250 || (port >= 7652 && port <= 7665); };
  EXPECT_EQ(unusedParticipantId(0, PortMapping{}, next_more_in_use), 128);
  // GIVEN both ranges full THEN there is no id (Fast DDS then picks one itself); the domain after next is not touched
  const auto two_taken = [](int port) { return port < 7400 + 2 * 250; };
  EXPECT_EQ(unusedParticipantId(0, PortMapping{}, two_taken), std::nullopt);
  EXPECT_EQ(unusedParticipantId(0, PortMapping{}, [](int) { return true; }), std::nullopt);
  // GIVEN the last domain (232: ports from 65400) THEN its last id is 62 (65534 / 65535), and none lies past it
  EXPECT_EQ(unusedParticipantId(232, PortMapping{}, [](int port) { return port < 65534; }), 62);
  EXPECT_EQ(unusedParticipantId(232, PortMapping{}, [](int port) { return port < 65536; }), std::nullopt);
  // GIVEN a profile with another mapping WHEN choosing THEN its gains are used
  PortMapping wide;
  wide.participant_gain = 4;
  const std::set<int> taken{7410, 7411};
  EXPECT_EQ(unusedParticipantId(0, wide, [&](int port) { return taken.count(port) > 0; }), 1);
  const std::set<int> second{7414};  // id 1 under gain 4: 7414 / 7415
  EXPECT_EQ(unusedParticipantId(0, wide, [&](int port) { return second.count(port) > 0; }), 0);
}

// ---- udp_port.h -------------------------------------------------------------------------------------------------

TEST(UdpPort, APortBoundByAnotherSocketIsInUseAndTheSearchGoesPastIt) {
  // GIVEN a UDP socket bound (without SO_REUSEADDR) to a port the kernel chose
  const int fd = ::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  ASSERT_GE(fd, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_ANY);
  ASSERT_EQ(::bind(fd, reinterpret_cast<const sockaddr*>(&address), sizeof address), 0);
  socklen_t size = sizeof address;
  ASSERT_EQ(::getsockname(fd, reinterpret_cast<sockaddr*>(&address), &size), 0);
  const int port = ntohs(address.sin_port);
  // THEN it is in use, and the first free port from it is another one
  EXPECT_TRUE(app::udpPortInUse(port));
  const std::optional<int> free_port = app::firstFreeUdpPort(port, 100);
  ASSERT_TRUE(free_port.has_value());
  EXPECT_GT(*free_port, port);
  // AND a range holding only that port has none free, nor one past port 65535
  EXPECT_EQ(app::firstFreeUdpPort(port, 1), std::nullopt);
  EXPECT_EQ(app::firstFreeUdpPort(65536, 10), std::nullopt);
  ::close(fd);
}

// ---- deafPorts (shm_ports.h) ------------------------------------------------------------------------------------

// Lines of /proc/<pid>/maps as Linux writes them (address range, permissions, offset, device, inode, path).
std::string mapping(const std::string& path) {
  return "7f2c1a000000-7f2c1a400000 rw-s 00000000 00:1a 4711                       " + path + "\n";
}

TEST(DeafPorts, AnOwnPortMappedOnlyDeletedWhileItsFileExistsIsDeaf) {
  // GIVEN a process listening on 7411 and 7412 and writing to a peer's 7413
  const std::string maps = "55d0c0a00000-55d0c0a21000 r-xp 00000000 08:01 1234 /usr/bin/swa_sim\n" +
                           mapping("/dev/shm/fastrtps_port7411 (deleted)") + mapping("/dev/shm/fastrtps_port7412") +
                           mapping("/dev/shm/fastrtps_port7413 (deleted)") + mapping("/dev/shm/fastrtps_port7411_el") +
                           mapping("/dev/shm/sem.fastrtps_port7411_mutex");
  const auto every = [](int) { return true; };
  // THEN its port 7411, mapped only as deleted while a new file exists, is deaf; 7412 is live; the peer's 7413 is
  // not its own, and the port's other files do not count
  EXPECT_EQ(deafPorts(maps, {7411, 7412}, every), (std::vector<int>{7411}));
  // WHEN no file of that name exists any more (the port was removed, not re-created) THEN nobody can write to it
  EXPECT_TRUE(deafPorts(maps, {7411, 7412}, [](int port) { return port != 7411; }).empty());
}

TEST(DeafPorts, AnOwnerThatMovedToTheNewSegmentHearsIt) {
  // GIVEN the old segment still mapped (deleted) beside the new one of the same name
  const std::string maps = mapping("/dev/shm/fastrtps_port7411 (deleted)") + mapping("/dev/shm/fastrtps_port7411");
  // THEN it hears: the owner follows a re-created port as Fast DDS intends
  EXPECT_TRUE(deafPorts(maps, {7411}, [](int) { return true; }).empty());
  // AND a port it never mapped, or a process without shared memory, says nothing
  EXPECT_TRUE(deafPorts(maps, {7500}, [](int) { return true; }).empty());
  EXPECT_TRUE(deafPorts("", {7411}, [](int) { return true; }).empty());
  EXPECT_TRUE(deafPorts(maps, {}, [](int) { return true; }).empty());
}

// ---- DeafPortWatch (deaf_port_watch.h) ---------------------------------------------------------------------------

TEST(DeafPortWatch, NamesEachDeafPortOnceLooksAtMostOncePerPeriodAndForgetsOnReset) {
  // GIVEN a process listening on 7411, 7412 and 7413, of which 7411 and 7412 are deaf, counting the looks
  std::vector<int> own{7411, 7412, 7413}, deaf{7411, 7412};
  int own_looks = 0, looks = 0;
  DeafPortWatch watch({[&] {
                         ++own_looks;
                         return own;
                       },
                       [&](const std::vector<int>& among) {
                         ++looks;
                         EXPECT_EQ(among, own);
                         return deaf;
                       }},
                      std::chrono::milliseconds(250));
  const DeafPortWatch::Clock::time_point t0{};
  // THEN the first poll names one, and a poll within the period does not look again
  EXPECT_EQ(watch.poll(t0), 7411);
  EXPECT_EQ(watch.poll(t0 + std::chrono::milliseconds(249)), std::nullopt);
  EXPECT_EQ(looks, 1);
  // AND the next period names the other, then neither again while they stay deaf (the caller could not re-create)
  EXPECT_EQ(watch.poll(t0 + std::chrono::milliseconds(250)), 7412);
  EXPECT_EQ(watch.poll(t0 + std::chrono::milliseconds(500)), std::nullopt);
  EXPECT_EQ(looks, 3);
  // AND its own ports were found once, at the first look
  EXPECT_EQ(own_looks, 1);
  // WHEN the participant is re-created (reset) on other ports, and one of them is found deaf THEN that is a new
  // deafness, among the new ports
  watch.reset();
  own = {7421, 7422};
  deaf = {7421};
  EXPECT_EQ(watch.poll(t0 + std::chrono::milliseconds(750)), 7421);
  EXPECT_EQ(own_looks, 2);
  // AND once re-created on the same numbers, the same port deaf again is named again
  watch.reset();
  EXPECT_EQ(watch.poll(t0 + std::chrono::seconds(1)), 7421);
  // AND a process that hears every port is never told otherwise
  deaf.clear();
  watch.reset();
  EXPECT_EQ(watch.poll(t0 + std::chrono::milliseconds(1250)), std::nullopt);
}

TEST(DeafPortWatch, AProcessWithoutSharedMemoryPortsIsNotLookedAt) {
  // GIVEN a process on UDP only: no port of its own
  int looks = 0;
  DeafPortWatch watch({[] { return std::vector<int>{}; },
                       [&](const std::vector<int>&) {
                         ++looks;
                         return std::vector<int>{7411};
                       }});
  // THEN it is never deaf, and its mappings are not even read
  EXPECT_EQ(watch.poll(DeafPortWatch::Clock::time_point{}), std::nullopt);
  EXPECT_EQ(looks, 0);
}

TEST(DeafPortWatch, ThisProcessWithoutSharedMemoryIsNeverDeaf) {
  // GIVEN the watch on this very process, which holds no Fast DDS port (no participant here)
  DeafPortWatch watch;
  // THEN it names nothing
  EXPECT_EQ(watch.poll(DeafPortWatch::Clock::now()), std::nullopt);
  EXPECT_EQ(deafPortReason(7411, "agents").rfind("deaf on shared-memory port 7411: ", 0), 0u);
}

TEST(OwnPorts, APortIsOwnWhenThisProcessHoldsTheLockOfItsExclusiveReadLockFile) {
  // GIVEN paths a process has open: only a port's exclusive-read lock file names a port
  EXPECT_EQ(lockFilePort("/dev/shm/fastrtps_port51920_el"), 51920);
  for (const char* other : {"/dev/shm/fastrtps_port51650_sl", "/dev/shm/fastrtps_31d336c7463b45ca_el",
                            "/dev/shm/fastrtps_port_el", "/dev/shm/fastrtps_port12a_el",
                            "/tmp/dev/shm/fastrtps_port1_el", "socket:[123456]", "/dev/shm/fastrtps_port51920"}) {
    EXPECT_FALSE(lockFilePort(other)) << other;
  }
  // AND /proc/locks: this process (22855) holds two locks, another process one, and 22855 waits for a third
  const std::string locks =
      "1: FLOCK  ADVISORY  WRITE 22855 00:1b:229995 0 EOF\n"
      "2: FLOCK  ADVISORY  WRITE 22854 00:1b:229988 0 EOF\n"
      "3: POSIX  ADVISORY  WRITE 22855 00:1b:229977 0 EOF\n"
      "4: FLOCK  ADVISORY  WRITE 22854 00:1b:229900 0 EOF\n"
      "4: -> FLOCK  ADVISORY  WRITE 22855 00:1b:229900 0 EOF\n";
  // THEN its own are the two it holds, not the one it waits for
  EXPECT_EQ(lockedInodes(locks, 22855), (std::set<unsigned long>{229995, 229977}));
  EXPECT_TRUE(lockedInodes(locks, 1).empty());
  EXPECT_TRUE(lockedInodes("", 22855).empty());
}

}  // namespace
}  // namespace swa::dds

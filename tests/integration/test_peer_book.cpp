// The participant book of swa/dds/peer_book.h: the card every SWA participant announces, twins (same name, same
// swarm) and who gives way, peers back after their lease expired. Pure, no DDS traffic (label unit).

#include <gtest/gtest.h>

#include <string>

#include "swa/dds/peer_book.h"

namespace swa::dds {
namespace {

PeerKey key(std::uint8_t b) {
  PeerKey k{};
  k.fill(b);
  return k;
}

PeerCard card(const std::string& swarm, std::int64_t started_ns, long pid = 100, const std::string& host = "h") {
  return PeerCard{swarm, started_ns, pid, host};
}

TEST(PeerCard, RoundTripsAndRejectsWhatIsNotACard) {
  const PeerCard c = card("run-7", 1'700'000'000'123'456'789, 4242, "drone-3");
  const auto back = decodePeerCard(encodePeerCard(c));
  ASSERT_TRUE(back);
  EXPECT_EQ(back->swarm, "run-7");
  EXPECT_EQ(back->started_ns, c.started_ns);
  EXPECT_EQ(back->pid, 4242);
  EXPECT_EQ(back->host, "drone-3");

  EXPECT_FALSE(decodePeerCard(""));
  EXPECT_FALSE(decodePeerCard("ros2 user data"));
  EXPECT_FALSE(decodePeerCard("swa-peer/1;started_ns=abc;pid=1;swarm=;host="));
  EXPECT_FALSE(decodePeerCard("swa-peer/1;started_ns=1;pid=1;swarm="));  // no host
  EXPECT_FALSE(decodePeerCard("swa-peer/1;started_ns=1;pid=1;swarm=;host=" + std::string(300, 'x')));
  // A later version's extra key is ignored.
  EXPECT_TRUE(decodePeerCard("swa-peer/1;started_ns=1;pid=1;swarm=;host=h;role=agent"));
}

TEST(PeerCard, SeparatorsInValuesAndLongHostsCannotBreakTheFormat) {
  const std::string text = encodePeerCard(card("a;b=c", 5, 1, std::string(400, 'h')));
  EXPECT_LE(text.size(), 255u);
  const auto back = decodePeerCard(text);
  ASSERT_TRUE(back);
  EXPECT_EQ(back->swarm, "a_b_c");
  EXPECT_EQ(back->started_ns, 5);
}

TEST(PeerBook, TwinIsSameNameSameSwarmAndTheYoungerGivesWay) {
  // GIVEN agent 3 of swarm "s", started at t = 100
  PeerBook book("swa_agent_3", card("s", 100), key(5));
  // WHEN others appear: another id, the same id in another swarm, and a non-SWA participant with our name
  book.discovered({key(1), "swa_agent_4", card("s", 50)});
  book.discovered({key(2), "swa_agent_3", card("other", 50)});
  book.discovered({key(3), "swa_agent_3", std::nullopt});
  // THEN none of them is a twin
  EXPECT_FALSE(book.oldestTwin());
  EXPECT_FALSE(book.mustGiveWay());

  // WHEN a younger agent 3 joins our swarm THEN it is our twin, and we stay
  book.discovered({key(4), "swa_agent_3", card("s", 200)});
  ASSERT_TRUE(book.oldestTwin());
  EXPECT_EQ(book.oldestTwin()->key, key(4));
  EXPECT_FALSE(book.mustGiveWay());

  // WHEN an older one is there too THEN we give way (and it is the twin named)
  book.discovered({key(6), "swa_agent_3", card("s", 99)});
  EXPECT_EQ(book.oldestTwin()->key, key(6));
  EXPECT_TRUE(book.mustGiveWay());

  // WHEN it leaves THEN we stay again
  book.lost(key(6), false);
  EXPECT_FALSE(book.mustGiveWay());
}

// A younger twin gives way at once; on a loaded host it was discovered and gone again between two polls of the agent,
// whose log then never said that a second agent had tried to run (CI, issue #46).
TEST(PeerBook, AYoungerTwinIsReportedOnceEvenIfItLeftBeforeTheNodeAsked) {
  // GIVEN agent 3 of swarm "s", started at t = 100
  PeerBook book("swa_agent_3", card("s", 100), key(5));
  // WHEN a younger agent 3 joins and leaves before anyone asks, and others come that are no younger twin
  book.discovered({key(4), "swa_agent_3", card("s", 200, 77, "drone-3")});
  book.lost(key(4), false);
  book.discovered({key(6), "swa_agent_3", card("s", 99)});       // older: we give way, it did not try to join us
  book.discovered({key(7), "swa_agent_3", card("other", 300)});  // another swarm
  book.discovered({key(8), "swa_agent_4", card("s", 300)});      // another id
  book.discovered({key(5), "swa_agent_3", card("s", 100)});      // our own announcement
  // THEN the one that left is still reported, with its card, and only it
  const std::vector<Peer> twins = book.takeYoungerTwins();
  ASSERT_EQ(twins.size(), 1u);
  EXPECT_EQ(twins[0].key, key(4));
  EXPECT_EQ(twins[0].card->pid, 77);
  EXPECT_EQ(twins[0].card->host, "drone-3");
  // AND once: the next call has nothing
  EXPECT_TRUE(book.takeYoungerTwins().empty());

  // WHEN a live younger twin announces itself again (a changed QoS) THEN it is not a second one
  book.discovered({key(9), "swa_agent_3", card("s", 400)});
  book.discovered({key(9), "swa_agent_3", card("s", 400)});
  EXPECT_EQ(book.takeYoungerTwins().size(), 1u);
}

TEST(PeerBook, TheReportOfYoungerTwinsIsBounded) {
  PeerBook book("swa_sim", card("", 1), key(0));
  // A restart loop of twins nobody asks about: the book keeps the newest kMaxExpired
  for (int i = 0; i < 3000; ++i) {
    PeerKey k{};
    k[0] = static_cast<std::uint8_t>(i & 0xff);
    k[1] = static_cast<std::uint8_t>((i >> 8) & 0xff);
    k[2] = 1;
    book.discovered({k, "swa_sim", card("", 2 + i)});
    book.lost(k, false);
  }
  const std::vector<Peer> twins = book.takeYoungerTwins();
  ASSERT_EQ(twins.size(), PeerBook::kMaxExpired);
  EXPECT_EQ(twins.back().card->started_ns, 2 + 2999);
}

TEST(PeerBook, EqualStartsAreBrokenByTheKeyTheSameWayOnBothSides) {
  PeerBook a("swa_sim", card("", 7), key(1));
  PeerBook b("swa_sim", card("", 7), key(2));
  a.discovered({key(2), "swa_sim", card("", 7)});
  b.discovered({key(1), "swa_sim", card("", 7)});
  EXPECT_FALSE(a.mustGiveWay());
  EXPECT_TRUE(b.mustGiveWay());
}

TEST(PeerBook, OurOwnAnnouncementIsNotATwin) {
  PeerBook book("swa_agent_0", card("", 1), key(9));
  book.discovered({key(9), "swa_agent_0", card("", 1)});
  EXPECT_FALSE(book.oldestTwin());
}

TEST(PeerBook, CountsPeersBackAfterTheirLeaseExpiredButNotAfterAGoodbye) {
  PeerBook book("swa_agent_0", card("", 1), key(9));
  book.discovered({key(1), "swa_sim", card("", 1)});
  book.discovered({key(2), "swa_monitor", card("", 1)});
  // A clean goodbye and a return (not possible for one GUID in practice, but not a lease case either)
  book.lost(key(2), false);
  book.discovered({key(2), "swa_monitor", card("", 1)});
  EXPECT_EQ(book.returnedAfterLease(), 0);
  // Silent beyond the lease, then back
  book.lost(key(1), true);
  EXPECT_EQ(book.returnedAfterLease(), 0);
  book.discovered({key(1), "swa_sim", card("", 1)});
  EXPECT_EQ(book.returnedAfterLease(), 1);
  EXPECT_EQ(book.lastReturned(), "swa_sim");
  EXPECT_EQ(book.lastReturnedKey(), key(1));  // the agent asks whether this participant reads its commands
  // Every departure, goodbye or lease, is handed out once, in order (the command gate frees the say of its writers)
  EXPECT_EQ(book.takeGone(), (std::vector<PeerKey>{key(2), key(1)}));
  EXPECT_TRUE(book.takeGone().empty());
  // A QoS change announcement of a live peer is not a return
  book.discovered({key(1), "swa_sim", card("", 1)});
  EXPECT_EQ(book.returnedAfterLease(), 1);
}

TEST(PeerBook, APeerOfAnotherSwarmBackAfterItsLeaseIsNotCounted) {
  // GIVEN our swarm "a", a peer of swarm "b", one of ours and one without a card (another vendor's bridge)
  PeerBook book("swa_agent_0", card("a", 1), key(9));
  book.discovered({key(1), "swa_sim", card("b", 1)});
  book.discovered({key(2), "swa_sim", card("a", 1)});
  book.discovered({key(3), "px4_bridge_0", std::nullopt});
  // WHEN the other swarm's simulator is silent beyond its lease and comes back
  book.lost(key(1), true);
  book.discovered({key(1), "swa_sim", card("b", 1)});
  // THEN that is nothing to us
  EXPECT_EQ(book.returnedAfterLease(), 0);
  // WHEN ours and the card-less one do the same THEN both count
  book.lost(key(2), true);
  book.discovered({key(2), "swa_sim", card("a", 1)});
  book.lost(key(3), true);
  book.discovered({key(3), "px4_bridge_0", std::nullopt});
  EXPECT_EQ(book.returnedAfterLease(), 2);
  EXPECT_EQ(book.lastReturned(), "px4_bridge_0");
}

TEST(PeerBook, MemoryOfExpiredPeersIsBounded) {
  PeerBook book("swa_sim", card("", 1), key(0));
  // 5000 crashed agents that never come back: the book remembers at most kMaxExpired, and a peer lost last is
  // still known when it returns.
  for (int i = 0; i < 5000; ++i) {
    PeerKey k{};
    k[0] = static_cast<std::uint8_t>(i & 0xff);
    k[1] = static_cast<std::uint8_t>((i >> 8) & 0xff);
    k[2] = 1;
    book.discovered({k, "swa_agent_" + std::to_string(i), card("", 1)});
    book.lost(k, true);
  }
  EXPECT_EQ(book.expiredRemembered(), PeerBook::kMaxExpired);
  PeerKey last{};
  last[0] = static_cast<std::uint8_t>(4999 & 0xff);
  last[1] = static_cast<std::uint8_t>((4999 >> 8) & 0xff);
  last[2] = 1;
  book.discovered({last, "swa_agent_4999", card("", 1)});
  EXPECT_EQ(book.returnedAfterLease(), 1);
}

}  // namespace
}  // namespace swa::dds

// When a secured node re-creates its participant (swa/dds/handshake_watch.h): only before it started and while what
// it needs is unmatched, after 5 s without an authentication (then 10, 20, 40, 60 s), and never later than 60 s after
// its creation while its peers keep authenticating (issue #46: the fixed schedule fed a reconnection storm).

#include <optional>

#include <gtest/gtest.h>

#include "swa/dds/handshake_watch.h"

namespace swa::dds {
namespace {

using Clock = HandshakeWatch::Clock;
using std::chrono::milliseconds;
using std::chrono::seconds;

class HandshakeWatchTest : public ::testing::Test {
 protected:
  void SetUp() override { watch.connected(t0); }

  // The first time in [from, to) (100 ms steps) at which the watch says stalled, given the last authentication.
  std::optional<Clock::duration> firstStall(Clock::duration from, Clock::duration to,
                                            Clock::time_point last_progress = {}) {
    for (Clock::duration t = from; t < to; t += milliseconds(100)) {
      if (watch.stalled(false, false, t0 + t, last_progress)) return t;
    }
    return std::nullopt;
  }

  HandshakeWatch watch{true};
  Clock::time_point t0 = Clock::time_point() + seconds(1000);
};

TEST_F(HandshakeWatchTest, WithoutSecurityOrOnceStartedOrMatchedItNeverReconnects) {
  HandshakeWatch plain(false);
  plain.connected(t0);
  EXPECT_FALSE(plain.stalled(false, false, t0 + seconds(600)));
  EXPECT_FALSE(watch.stalled(true, false, t0 + seconds(600)));
  EXPECT_FALSE(watch.stalled(false, true, t0 + seconds(600)));
  EXPECT_EQ(watch.reconnects(), 0);
}

TEST_F(HandshakeWatchTest, WithNoAuthenticationAtAllItReconnectsAfter5sThen10s) {
  EXPECT_EQ(firstStall(seconds(0), seconds(30)), seconds(5));
  watch.connected(t0 + seconds(5));
  EXPECT_EQ(firstStall(seconds(5), seconds(40)), seconds(15));
  EXPECT_EQ(watch.reconnects(), 2);
}

TEST_F(HandshakeWatchTest, HandshakesStillCompletingPostponeTheReconnection) {
  // GIVEN a slow start: a peer authenticated 3, 6 and 9 s after the participant was created
  for (const int at : {3, 6, 9}) {
    const Clock::time_point progress = t0 + seconds(at);
    // THEN nothing before 5 s of quiet after each
    EXPECT_EQ(firstStall(seconds(at), seconds(at + 3), progress), std::nullopt) << at;
  }
  // AND once they stop, 5 s after the last one
  EXPECT_EQ(firstStall(seconds(12), seconds(30), t0 + seconds(9)), seconds(14));
}

TEST_F(HandshakeWatchTest, PeersThatKeepAuthenticatingDelayItNoLongerThan60s) {
  // GIVEN a peer authenticating every second (others reconnecting), while what this node needs stays unmatched
  std::optional<Clock::duration> stall;
  for (Clock::duration t = seconds(0); t < seconds(120) && !stall; t += milliseconds(100)) {
    const Clock::time_point progress = t0 + std::chrono::duration_cast<seconds>(t);
    if (watch.stalled(false, false, t0 + t, progress)) stall = t;
  }
  // THEN it reconnects 60 s after its creation
  EXPECT_EQ(stall, seconds(60));
}

TEST_F(HandshakeWatchTest, AnAuthenticationOfAnEarlierParticipantDoesNotCount) {
  // The progress is older than this participant: the wait counts from its creation.
  EXPECT_EQ(firstStall(seconds(0), seconds(30), t0 - seconds(2)), seconds(5));
}

}  // namespace
}  // namespace swa::dds

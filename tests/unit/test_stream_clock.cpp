// Stamp rules of one input stream (issue #11): future stamps beyond the window are rejected, a producer whose clock
// restarts is followed after a few consistent samples, duplicates and random stamps never take over.

#include <cstdint>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include "swa/agent/stream_clock.h"

namespace swa::agent {
namespace {

using V = StreamClock::Verdict;
constexpr StampNs kMs = 1'000'000;
constexpr StampNs kSec = 1'000'000'000;
constexpr StampNs kWindow = kSec;  // limits.max_stamp_jump_s

StreamClock at100Hz(int n) {  // n samples every 10 ms from t = 5 s
  StreamClock c(kWindow, 3);
  for (int i = 0; i < n; ++i) EXPECT_EQ(c.check(5 * kSec + i * 10 * kMs), V::kAccept);
  return c;
}

TEST(StreamClock, IncreasingStampsWithinTheWindowAreAccepted) {
  StreamClock c = at100Hz(100);
  EXPECT_EQ(c.last(), 5 * kSec + 990 * kMs);
  EXPECT_EQ(c.check(c.last() + kWindow), V::kAccept);  // a gap of exactly the window is still the same timeline
  EXPECT_EQ(c.resyncs(), 0u);
}

TEST(StreamClock, OneFutureStampIsRejectedAndTheStreamGoesOn) {
  // GIVEN a 100 Hz stream
  StreamClock c = at100Hz(10);
  const StampNs last = c.last();
  // WHEN one sample is stamped 60 s ahead, and one INT64_MAX
  EXPECT_EQ(c.check(last + 60 * kSec), V::kFuture);
  EXPECT_EQ(c.check(std::numeric_limits<StampNs>::max()), V::kFuture);
  // THEN the next genuine samples are accepted at once: no hover for 60 s
  EXPECT_EQ(c.check(last + 10 * kMs), V::kAccept);
  EXPECT_EQ(c.check(last + 20 * kMs), V::kAccept);
  EXPECT_EQ(c.resyncs(), 0u);
}

TEST(StreamClock, ProducerRestartIsFollowedAfterThreeConsistentSamples) {
  // GIVEN a stream at t ~ 5 s whose producer restarts its clock at 0
  StreamClock c = at100Hz(10);
  // WHEN the restarted producer sends 0, 10, 20 ms
  EXPECT_EQ(c.check(0), V::kOutOfOrder);
  EXPECT_EQ(c.check(10 * kMs), V::kOutOfOrder);
  // THEN the third is accepted as a re-synchronisation, counted, and the stream goes on from there
  EXPECT_EQ(c.check(20 * kMs), V::kResync);
  EXPECT_EQ(c.resyncs(), 1u);
  EXPECT_EQ(c.check(30 * kMs), V::kAccept);
  // AND samples of the old timeline are now the ones rejected
  EXPECT_EQ(c.check(5 * kSec + 100 * kMs), V::kFuture);
}

TEST(StreamClock, AcceptedBogusFutureStampIsRepairedByTheGenuineStream) {
  // GIVEN a stream that accepted one sample 0.9 s ahead (inside the window: indistinguishable from a gap)
  StreamClock c = at100Hz(10);
  const StampNs genuine = c.last();
  EXPECT_EQ(c.check(genuine + 900 * kMs), V::kAccept);
  // WHEN the genuine samples go on
  EXPECT_EQ(c.check(genuine + 10 * kMs), V::kOutOfOrder);
  EXPECT_EQ(c.check(genuine + 20 * kMs), V::kOutOfOrder);
  // THEN three of them take the stream back
  EXPECT_EQ(c.check(genuine + 30 * kMs), V::kResync);
  EXPECT_EQ(c.check(genuine + 40 * kMs), V::kAccept);
}

TEST(StreamClock, StaleFloodInANarrowRangeDoesNotResynchronise) {
  // GIVEN a 100 Hz stream at ~5 s and a flood of stale samples with random stamps from the last 5 s, 100 between
  // consecutive genuine samples
  StreamClock c(kWindow, 4);
  for (int i = 0; i < 100; ++i) c.check(5 * kSec + i * 10 * kMs);
  std::mt19937_64 rng(3);
  std::uniform_int_distribution<StampNs> stale(0, 5 * kSec);
  int genuine_rejected = 0;
  for (int step = 100; step < 1100; ++step) {
    for (int j = 0; j < 100; ++j) c.check(stale(rng));
    genuine_rejected += c.check(5 * kSec + step * 10 * kMs) == V::kAccept ? 0 : 1;
  }
  // THEN the stale timeline never takes over (its steps rarely fall within a factor 2 of the 10 ms period, never 3
  // times in a row), and every genuine sample is accepted
  EXPECT_EQ(c.resyncs(), 0u);
  EXPECT_EQ(genuine_rejected, 0);
}

TEST(StreamClock, RestartMustKeepTheStreamsRate) {
  // GIVEN a 100 Hz stream at ~5 s, and samples of a new timeline at 100 s stepping 1 s (within the window, but not
  // at the stream's 10 ms period)
  StreamClock c = at100Hz(50);
  for (int i = 0; i < 10; ++i) EXPECT_EQ(c.check(100 * kSec + i * kSec), V::kFuture);
  // THEN no resync; a timeline at 200 s stepping 10 ms re-synchronises on its third sample
  EXPECT_EQ(c.check(200 * kSec), V::kFuture);
  EXPECT_EQ(c.check(200 * kSec + 10 * kMs), V::kFuture);
  EXPECT_EQ(c.check(200 * kSec + 20 * kMs), V::kResync);
}

TEST(StreamClock, DuplicatesAndRandomStampsNeverResynchronise) {
  StreamClock c = at100Hz(10);
  const StampNs last = c.last();
  for (int i = 0; i < 1000; ++i) EXPECT_EQ(c.check(last), V::kOutOfOrder);  // a flood of one duplicate
  std::mt19937_64 rng(11);
  std::uniform_int_distribution<StampNs> any(std::numeric_limits<StampNs>::min(), std::numeric_limits<StampNs>::max());
  int accepted = 0;
  for (int i = 0; i < 100000; ++i) {
    const V v = c.check(any(rng));
    accepted += (v == V::kAccept || v == V::kResync) ? 1 : 0;
  }
  // Random 64-bit stamps land within 1 s after the last one with probability ~1e-10 each: none in 1e5
  EXPECT_EQ(accepted, 0);
  EXPECT_EQ(c.resyncs(), 0u);
  EXPECT_EQ(c.check(last + 10 * kMs), V::kAccept);
}

TEST(StreamClock, InterruptedCandidateTimelineStartsOver) {
  StreamClock c = at100Hz(10);
  EXPECT_EQ(c.check(0), V::kOutOfOrder);
  EXPECT_EQ(c.check(10 * kMs), V::kOutOfOrder);
  EXPECT_EQ(c.check(c.last() + 10 * kMs), V::kAccept);  // the genuine stream interrupts: the count restarts
  EXPECT_EQ(c.check(20 * kMs), V::kOutOfOrder);
  EXPECT_EQ(c.check(30 * kMs), V::kOutOfOrder);
  EXPECT_EQ(c.check(40 * kMs), V::kResync);
}

TEST(StreamClock, AResumedStreamGoesOnFromTheResumedStampAtItsOldRate) {
  // GIVEN a 100 Hz stream, silent for 3 s, whose next stamp another clock vouches for
  StreamClock c = at100Hz(10);
  const StampNs back = c.last() + 3000 * kMs;
  EXPECT_EQ(c.check(back), V::kFuture);
  // WHEN it resumes there
  c.resume(back);
  // THEN it goes on from it at 100 Hz, and the silence was no resynchronisation
  EXPECT_EQ(c.last(), back);
  EXPECT_EQ(c.check(back + 10 * kMs), V::kAccept);
  EXPECT_EQ(c.check(back + 5 * kMs), V::kOutOfOrder);
  EXPECT_EQ(c.resyncs(), 0u);
}

TEST(StreamClock, ExtremeStampsDoNotOverflow) {
  StreamClock c(kWindow, 3);
  EXPECT_EQ(c.check(std::numeric_limits<StampNs>::min()), V::kAccept);
  EXPECT_EQ(c.check(std::numeric_limits<StampNs>::max()), V::kFuture);
  EXPECT_EQ(c.check(std::numeric_limits<StampNs>::min() + kMs), V::kAccept);
}

}  // namespace
}  // namespace swa::agent

// swa/dds/deadline.h: what ends a process whose participant Fast DDS cannot delete (participant_shutdown.cpp).

#include "swa/dds/deadline.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <future>

namespace swa::dds {
namespace {

TEST(Deadline, ACallThatOutlastsItsLimitRunsTheExpiryOnce) {
  std::promise<void> expired;
  std::future<void> expired_future = expired.get_future();
  std::atomic<int> runs{0};
  {
    const Deadline d(std::chrono::milliseconds(20), [&] {
      ++runs;
      expired.set_value();
    });
    // the "call": it returns only once the expiry has run (bounded: a broken Deadline fails here, it does not hang)
    ASSERT_EQ(expired_future.wait_for(std::chrono::seconds(30)), std::future_status::ready);
  }
  EXPECT_EQ(runs.load(), 1);
}

TEST(Deadline, ACallThatReturnsInTimeNeverRunsTheExpiryAndIsNotHeldUp) {
  std::atomic<int> runs{0};
  const auto start = std::chrono::steady_clock::now();
  {
    const Deadline d(std::chrono::hours(1), [&] { ++runs; });
  }
  // destroyed at once: its thread was woken, not left to wait out the hour
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::minutes(1));
  EXPECT_EQ(runs.load(), 0);
}

}  // namespace
}  // namespace swa::dds

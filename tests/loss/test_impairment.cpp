// The loss emulator's decisions (tests/loss/impairment.h): the fraction dropped and the delays held, over a fixed
// seed; the release queue's order.

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "impairment.h"

namespace swa::netem {
namespace {

using std::chrono::microseconds;

TEST(Impairment, DropsTheGivenFractionAndDelaysTheRestUniformly) {
  for (const double loss : {0.1, 0.3}) {
    Impairment imp({loss, microseconds(20'000), microseconds(10'000), 7});
    const int n = 200'000;
    int dropped = 0;
    double sum_ms = 0.0, min_ms = 1e9, max_ms = 0.0;
    for (int k = 0; k < n; ++k) {
      const auto d = imp.decide();
      if (!d) {
        ++dropped;
        continue;
      }
      const double ms = static_cast<double>(d->count()) / 1000.0;
      sum_ms += ms;
      min_ms = std::min(min_ms, ms);
      max_ms = std::max(max_ms, ms);
    }
    // Binomial: sd of the fraction = sqrt(p(1-p)/n) < 0.0011; 0.005 is more than 4 sd.
    EXPECT_NEAR(static_cast<double>(dropped) / n, loss, 0.005);
    EXPECT_NEAR(sum_ms / (n - dropped), 20.0, 0.1);  // uniform on [10, 30]: sd of the mean 0.013 ms
    EXPECT_GE(min_ms, 10.0);
    EXPECT_LE(max_ms, 30.0);
    EXPECT_LT(min_ms, 10.1);
    EXPECT_GT(max_ms, 29.9);
  }
}

TEST(Impairment, SameSeedSameDecisions) {
  Impairment a({0.3, microseconds(20'000), microseconds(10'000), 42});
  Impairment b({0.3, microseconds(20'000), microseconds(10'000), 42});
  Impairment c({0.3, microseconds(20'000), microseconds(10'000), 43});
  int differ = 0;
  for (int k = 0; k < 1000; ++k) {
    const auto x = a.decide();
    EXPECT_EQ(x, b.decide());
    differ += x != c.decide() ? 1 : 0;
  }
  EXPECT_GT(differ, 100);
}

TEST(Impairment, NoLossNoDelayPassesEverythingAtOnce) {
  Impairment imp({0.0, microseconds(0), microseconds(0), 1});
  for (int k = 0; k < 1000; ++k) EXPECT_EQ(imp.decide(), microseconds(0));
}

TEST(Impairment, RejectsImpossibleSettings) {
  EXPECT_THROW(Impairment({1.0, microseconds(0), microseconds(0), 1}), std::invalid_argument);
  EXPECT_THROW(Impairment({-0.1, microseconds(0), microseconds(0), 1}), std::invalid_argument);
  EXPECT_THROW(Impairment({0.1, microseconds(5), microseconds(10), 1}), std::invalid_argument);
}

TEST(ReleaseQueue, ReleasesDuePacketsEarliestFirstAndKeepsTheRest) {
  ReleaseQueue q;
  const Clock::time_point t0{};
  q.hold(t0 + microseconds(30), 3);
  q.hold(t0 + microseconds(10), 1);
  q.hold(t0 + microseconds(20), 2);
  std::vector<std::uint32_t> out;
  EXPECT_EQ(q.releaseDue(t0 + microseconds(20), [&](std::uint32_t id) { out.push_back(id); }), 2u);
  EXPECT_EQ(out, (std::vector<std::uint32_t>{1, 2}));
  EXPECT_EQ(q.next(), t0 + microseconds(30));
  EXPECT_EQ(q.releaseDue(Clock::time_point::max(), [&](std::uint32_t id) { out.push_back(id); }), 1u);
  EXPECT_FALSE(q.next());
}

}  // namespace
}  // namespace swa::netem

// GNSS from the vehicle (swa/px4/gnss.h): PX4's GPS fix and local position validity become SWA's GNSS samples, a loss
// at once, valid ones at the agent's rate, bad numbers never valid.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "swa/px4/gnss.h"

namespace swa::px4::gnss_test {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

LocalPositionReport position(std::uint64_t t_us, bool xy_valid = true, double x = 3.0, double y = -4.0,
                             double eph = 0.8) {
  return {t_us, xy_valid, false, x, y, eph};
}

TEST(GnssForward, AFixAndAValidPositionGiveSwasSampleInEastNorthOnPx4sClock) {
  GnssForward f;
  f.onGps({1'000'000, kGpsFix3d});
  const auto g = f.onLocalPosition(position(1'050'000));
  ASSERT_TRUE(g);
  EXPECT_TRUE(g->valid);
  EXPECT_EQ(g->stamp_ns, 1'050'000'000);
  EXPECT_EQ(g->position_m.x(), -4.0);  // east = y_NED
  EXPECT_EQ(g->position_m.y(), 3.0);   // north = x_NED
  EXPECT_EQ(g->std_m, 0.8);
}

TEST(GnssForward, ALostFixOrPositionIsForwardedAtOnceAndARegainToo) {
  GnssForward f;
  f.onGps({0, kGpsFix3d});
  ASSERT_TRUE(f.onLocalPosition(position(10'000)));
  // WHEN the receiver loses its fix 10 ms later, well inside the 0.1 s rate limit
  f.onGps({15'000, 1});
  const auto lost = f.onLocalPosition(position(20'000));
  // THEN the loss goes out with the next position report
  ASSERT_TRUE(lost);
  EXPECT_FALSE(lost->valid);
  // AND the same for the autopilot's own verdict, with a fix present
  GnssForward g;
  g.onGps({0, 6});
  ASSERT_TRUE(g.onLocalPosition(position(10'000)));
  const auto invalid = g.onLocalPosition(position(20'000, /*xy_valid=*/false));
  ASSERT_TRUE(invalid);
  EXPECT_FALSE(invalid->valid);
  // AND a regain goes out at once too
  const auto back = g.onLocalPosition(position(30'000));
  ASSERT_TRUE(back);
  EXPECT_TRUE(back->valid);
  EXPECT_EQ(g.counters().not_xy_valid, 1u);
}

TEST(GnssForward, DeadReckoningIsNotAFixEvenWithXyValidAndAReceiverFix) {
  GnssForward f;
  f.onGps({0, kGpsFix3d});
  LocalPositionReport p = position(10'000);
  p.dead_reckoning = true;
  const auto g = f.onLocalPosition(p);
  ASSERT_TRUE(g);
  EXPECT_FALSE(g->valid);
  EXPECT_EQ(f.counters().dead_reckoning, 1u);
}

TEST(GnssForward, AFixFromBeforeAClockRestartIsNotFresh) {
  GnssForward f;
  f.onGps({50'000'000, kGpsFix3d});
  ASSERT_TRUE(f.onLocalPosition(position(50'000'000))->valid);
  // WHEN PX4 restarts and its receiver stays silent
  const auto g = f.onLocalPosition(position(20'000));
  // THEN the old fix does not count
  ASSERT_TRUE(g);
  EXPECT_FALSE(g->valid);
  // AND a GPS report far ahead of the position (a clock mix-up) is stale too
  GnssForward h;
  h.onGps({9'000'000, kGpsFix3d});
  EXPECT_FALSE(h.onLocalPosition(position(1'000'000))->valid);
}

TEST(GnssForward, NoGpsReportOrAStaleOneIsNoFix) {
  GnssForward f;
  const auto none = f.onLocalPosition(position(1'000'000));
  ASSERT_TRUE(none);
  EXPECT_FALSE(none->valid);
  f.onGps({1'000'000, kGpsFix3d});
  EXPECT_TRUE(f.onLocalPosition(position(1'100'000))->valid);
  // 1.2 s after the last GPS report: the receiver went quiet
  const auto stale = f.onLocalPosition(position(2'200'000));
  ASSERT_TRUE(stale);
  EXPECT_FALSE(stale->valid);
  EXPECT_EQ(f.counters().stale_gps, 1u);
  EXPECT_EQ(f.counters().no_fix, 1u);
}

TEST(GnssForward, BadNumbersAreNeverAValidSample) {
  for (const LocalPositionReport& bad : {position(0, true, kNaN), position(0, true, 1.0, INFINITY),
                                         position(0, true, 1.0, 2.0, 0.0), position(0, true, 1.0, 2.0, -1.0),
                                         position(0, true, 1.0, 2.0, kNaN)}) {
    GnssForward f;
    f.onGps({0, kGpsFix3d});
    LocalPositionReport p = bad;
    p.timestamp_us = 100;
    const auto g = f.onLocalPosition(p);
    ASSERT_TRUE(g);
    EXPECT_FALSE(g->valid);
    EXPECT_EQ(f.counters().bad_numbers, 1u);
  }
}

TEST(GnssForward, ValidSamplesComeAtTenHertzFromA100HzPositionStream) {
  GnssForward f;
  f.onGps({0, kGpsFix3d});
  int sent = 0;
  for (std::uint64_t t = 10'000; t <= 2'000'000; t += 10'000) {
    if (t % 200'000 == 0) f.onGps({t, kGpsFix3d});
    if (const auto g = f.onLocalPosition(position(t))) {
      EXPECT_TRUE(g->valid);
      ++sent;
    }
  }
  EXPECT_GE(sent, 19);
  EXPECT_LE(sent, 21);
}

TEST(GnssForward, OldReportsAreDroppedAndAClockRestartStartsAfresh) {
  GnssForward f;
  f.onGps({5'000'000, kGpsFix3d});
  ASSERT_TRUE(f.onLocalPosition(position(5'000'000)));
  EXPECT_FALSE(f.onLocalPosition(position(5'000'000)));  // not newer
  EXPECT_FALSE(f.onLocalPosition(position(4'500'000)));  // late
  EXPECT_EQ(f.counters().out_of_order, 2u);
  // WHEN PX4 reboots: its clock starts again near 0, and so does its GPS
  f.onGps({20'000, kGpsFix3d});
  const auto g = f.onLocalPosition(position(30'000));
  ASSERT_TRUE(g);
  EXPECT_TRUE(g->valid);
  EXPECT_EQ(g->stamp_ns, 30'000'000);
  EXPECT_EQ(f.counters().clock_restarts, 1u);
}

TEST(GnssForward, RandomReportsNeverGiveAValidSampleWithoutAFixAValidPositionAndFiniteNumbers) {
  std::mt19937_64 rng(27);
  std::uniform_int_distribution<int> fix(0, 6), coin(0, 1), kind(0, 5);
  std::uniform_real_distribution<double> value(-1e3, 1e3);
  GnssForward f;
  std::uint64_t t = 0;
  std::uint8_t last_fix = 0;
  for (int k = 0; k < 20000; ++k) {
    t += static_cast<std::uint64_t>(1000 + rng() % 20000);
    if (coin(rng)) {
      last_fix = static_cast<std::uint8_t>(fix(rng));
      f.onGps({t, last_fix});
    }
    LocalPositionReport p{t, coin(rng) == 1, false, value(rng), value(rng), std::abs(value(rng)) * 1e-2};
    switch (kind(rng)) {
      case 0: p.x_m = kNaN; break;
      case 1: p.eph_m = 0.0; break;
      case 2: p.y_m = -INFINITY; break;
      default: break;
    }
    if (const auto g = f.onLocalPosition(p); g && g->valid) {
      EXPECT_TRUE(p.xy_valid);
      EXPECT_GE(last_fix, kGpsFix3d);
      EXPECT_TRUE(std::isfinite(g->position_m.x()) && std::isfinite(g->position_m.y()));
      EXPECT_GT(g->std_m, 0.0);
    }
  }
  EXPECT_GT(f.counters().forwarded, 100u);
  EXPECT_GT(f.counters().invalid_forwarded, 100u);
}

}  // namespace
}  // namespace swa::px4::gnss_test

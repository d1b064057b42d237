// GNSS from the vehicle (swa/px4/gnss.h): PX4's GPS fix and local position validity become SWA's GNSS samples, a loss
// at once, valid ones at the agent's rate, bad numbers never valid; a moved local origin brought back into the first
// origin's frame through PX4's map projection (swa/px4/map_projection.h, issue #46).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "swa/px4/gnss.h"
#include "swa/px4/map_projection.h"

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
  for (const LocalPositionReport& bad :
       {position(0, true, kNaN), position(0, true, 1.0, INFINITY), position(0, true, 1.0, 2.0, 0.0),
        position(0, true, 1.0, 2.0, -1.0), position(0, true, 1.0, 2.0, kNaN)}) {
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
      case 0:
        p.x_m = kNaN;
        break;
      case 1:
        p.eph_m = 0.0;
        break;
      case 2:
        p.y_m = -INFINITY;
        break;
      default:
        break;
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

// --- PX4's map projection and a moved local origin (issue #46) ---

const GeoPoint kFirstOrigin{47.397742, 8.545594};

// PX4's own MapProjection::project (lib/geo), with its acos: the reference the careful form must agree with.
NedPoint px4Project(const GeoPoint& ref, const GeoPoint& p) {
  const double k_rad = M_PI / 180.0;
  const double lat0 = ref.lat_deg * k_rad, lat = p.lat_deg * k_rad, d_lon = (p.lon_deg - ref.lon_deg) * k_rad;
  const double arg =
      std::clamp(std::sin(lat0) * std::sin(lat) + std::cos(lat0) * std::cos(lat) * std::cos(d_lon), -1.0, 1.0);
  const double c = std::acos(arg);
  const double k = c > 0.0 ? c / std::sin(c) : 1.0;
  return {k * (std::cos(lat0) * std::sin(lat) - std::sin(lat0) * std::cos(lat) * std::cos(d_lon)) * 6371000.0,
          k * std::cos(lat) * std::sin(d_lon) * 6371000.0};
}

TEST(MapProjection, IsPx4sSphereAndARoundTripIsExactToNanometresOverKilometres) {
  const MapProjection frame(kFirstOrigin);
  // A thousandth of a degree of latitude is that arc of PX4's 6371 km sphere, not of WGS 84's meridian
  const NedPoint north = frame.project({kFirstOrigin.lat_deg + 1e-3, kFirstOrigin.lon_deg});
  EXPECT_NEAR(north.north_m, 6371000.0 * 1e-3 * M_PI / 180.0, 1e-9);
  EXPECT_NEAR(north.east_m, 0.0, 1e-9);
  for (const NedPoint p : {NedPoint{0.01, 0.0}, NedPoint{3.0, -4.0}, NedPoint{500.0, 0.0}, NedPoint{-250.0, 433.0},
                           NedPoint{4000.0, -7000.0}, NedPoint{-10000.0, 10000.0}}) {
    SCOPED_TRACE(std::to_string(p.north_m) + " m north, " + std::to_string(p.east_m) + " m east");
    // WHEN a point is placed on the ground and projected again
    const GeoPoint ground = frame.reproject(p);
    const NedPoint back = frame.project(ground);
    // THEN it is where it was, to a nanometre
    EXPECT_NEAR(back.north_m, p.north_m, 1e-9);
    EXPECT_NEAR(back.east_m, p.east_m, 1e-9);
    // AND where PX4's own formula puts it (whose acos loses digits near the reference: a millimetre is its own
    // precision there, far below the float32 metres PX4 sends)
    const NedPoint px4 = px4Project(kFirstOrigin, ground);
    EXPECT_NEAR(px4.north_m, p.north_m, 1e-3);
    EXPECT_NEAR(px4.east_m, p.east_m, 1e-3);
  }
  EXPECT_EQ(frame.project(kFirstOrigin).north_m, 0.0);
  EXPECT_FALSE(isProjectionReference({kNaN, 8.0}));
  EXPECT_FALSE(isProjectionReference({47.0, INFINITY}));
  EXPECT_FALSE(isProjectionReference({90.0, 8.0}));
  EXPECT_FALSE(isProjectionReference({47.0, 180.5}));
  EXPECT_TRUE(isProjectionReference({-89.9, -180.0}));
}

// A report at `t_us` of the point `ground` (fixed on the ground) as PX4 sends it with the origin `ref` set at
// `ref_us`: x, y are the point projected around that origin.
LocalPositionReport placed(std::uint64_t t_us, const GeoPoint& ground, const GeoPoint& ref, std::uint64_t ref_us) {
  const NedPoint p = MapProjection(ref).project(ground);
  LocalPositionReport r = position(t_us, true, p.north_m, p.east_m);
  r.xy_global = true;
  r.ref_timestamp_us = ref_us;
  r.ref_lat_deg = ref.lat_deg;
  r.ref_lon_deg = ref.lon_deg;
  return r;
}

// The position, east and north, a point on the ground has in the first origin's frame.
agent::Vec2 inFirstFrame(const GeoPoint& ground) {
  const NedPoint p = MapProjection(kFirstOrigin).project(ground);
  return {p.east_m, p.north_m};
}

TEST(GnssForward, AMovedOriginIsBroughtBackIntoTheFirstOriginsFrameExactlyCountedAndReportedOnce) {
  // GIVEN a vehicle flying north-east at 5 m/s from 30 m north, 40 m east of its first origin, with a fix
  const MapProjection first(kFirstOrigin);
  const auto ground = [&](std::uint64_t t_us) {
    const double s = static_cast<double>(t_us) * 1e-6 * 5.0 / std::sqrt(2.0);
    return first.reproject({30.0 + s, 40.0 + s});
  };
  // WHEN PX4 re-sets its origin 500 m east of the first at 2 s, then 300 m north-west of that one at 4 s, and
  // re-bases x, y on each (a jump of 500 m, then of 300 m, in what it sends)
  const GeoPoint second = first.reproject({0.0, 500.0});
  const GeoPoint third = MapProjection(second).reproject({300.0 / std::sqrt(2.0), -300.0 / std::sqrt(2.0)});
  GnssForward f;
  double worst_m = 0.0;
  std::vector<std::string> events;
  int forwarded = 0;
  for (std::uint64_t t = 100'000; t <= 6'000'000; t += 100'000) {
    f.onGps({t, kGpsFix3d});
    const LocalPositionReport r = t < 2'000'000   ? placed(t, ground(t), kFirstOrigin, 50'000)
                                  : t < 4'000'000 ? placed(t, ground(t), second, 2'000'000)
                                                  : placed(t, ground(t), third, 4'000'000);
    const auto g = f.onLocalPosition(r);
    for (std::string& e : f.takeEvents()) events.push_back(std::move(e));
    ASSERT_TRUE(g);
    ASSERT_TRUE(g->valid);
    ++forwarded;
    // THEN every sample is the point in the first origin's frame, to a micrometre, across both changes
    worst_m = std::max(worst_m, (g->position_m - inFirstFrame(ground(t))).norm());
  }
  EXPECT_LT(worst_m, 1e-6);
  EXPECT_EQ(forwarded, 60);
  // AND each change is counted and reported once, the new origin placed against the first
  EXPECT_EQ(f.counters().origin_changes, 2u);
  ASSERT_EQ(events.size(), 2u);
  EXPECT_EQ(events[0],
            "PX4 moved its local origin (ref_timestamp 50000 -> 2000000, 500.00 m east, 0.00 m north of the first): "
            "positions brought into the first origin's frame");
  // (not 500 - 212.13 east, 212.13 north: north at the second origin is turned 8.5e-5 rad against the first's, as the
  // meridians converge, 2.6 cm over 300 m; bringing back by the origins' difference alone would miss that)
  EXPECT_NE(events[1].find("(ref_timestamp 2000000 -> 4000000, 287.85 m east, 212.11 m north of the first)"),
            std::string::npos)
      << events[1];
  EXPECT_EQ(f.counters().unusable_reference, 0u);
}

TEST(GnssForward, AnOriginReSetInPlaceIsCountedAndTheNumbersPassUntouched) {
  GnssForward f;
  f.onGps({0, kGpsFix3d});
  ASSERT_TRUE(f.onLocalPosition(placed(100'000, kFirstOrigin, kFirstOrigin, 10)));
  // WHEN PX4 re-sets its origin at the same place (a new ref_timestamp only)
  LocalPositionReport r = placed(200'000, kFirstOrigin, kFirstOrigin, 150'000);
  r.x_m = 12.345;
  r.y_m = -6.789;
  const auto g = f.onLocalPosition(r);
  // THEN it is a change, but x, y are already in the first frame: not one rounding is added
  ASSERT_TRUE(g && g->valid);
  EXPECT_EQ(g->position_m.x(), -6.789);
  EXPECT_EQ(g->position_m.y(), 12.345);
  EXPECT_EQ(f.counters().origin_changes, 1u);
  ASSERT_EQ(f.takeEvents().size(), 1u);
  EXPECT_TRUE(f.takeEvents().empty());
}

TEST(GnssForward, AnUnusableReferenceAfterAFirstOneIsNoFixNeverAJump) {
  for (const int kind : {0, 1, 2}) {
    SCOPED_TRACE(kind);
    GnssForward f;
    f.onGps({0, kGpsFix3d});
    ASSERT_TRUE(f.onLocalPosition(placed(100'000, kFirstOrigin, kFirstOrigin, 10))->valid);
    // WHEN the reference becomes unusable (xy_global false, or ref_lat / ref_lon not a place) with x, y 500 m off
    LocalPositionReport r = placed(200'000, kFirstOrigin, kFirstOrigin, 10);
    r.x_m = 500.0;
    if (kind == 0) r.xy_global = false;
    if (kind == 1) r.ref_lat_deg = kNaN;
    if (kind == 2) r.ref_lon_deg = INFINITY;
    const auto g = f.onLocalPosition(r);
    // THEN it goes out at once as no fix, counted, reported once however long it lasts
    ASSERT_TRUE(g);
    EXPECT_FALSE(g->valid);
    r.timestamp_us = 250'000;
    EXPECT_FALSE(f.onLocalPosition(r));  // still invalid: nothing new to send within the period
    EXPECT_EQ(f.counters().unusable_reference, 2u);
    EXPECT_EQ(f.takeEvents().size(), 1u);
    // AND when the first origin's reference is back, so is the fix, in the first frame, and no change is counted
    const auto back = f.onLocalPosition(placed(400'000, kFirstOrigin, kFirstOrigin, 10));
    ASSERT_TRUE(back);
    EXPECT_TRUE(back->valid);
    EXPECT_EQ(back->position_m.norm(), 0.0);
    EXPECT_EQ(f.counters().origin_changes, 0u);
  }
}

TEST(GnssForward, APx4RebootStartsItsClockAfreshAndItsNewOriginIsBroughtBackToTheFirst) {
  const GeoPoint here = MapProjection(kFirstOrigin).reproject({120.0, -80.0});
  GnssForward f;
  f.onGps({50'000'000, kGpsFix3d});
  ASSERT_TRUE(f.onLocalPosition(placed(50'000'000, here, kFirstOrigin, 3'000'000))->valid);
  // WHEN PX4 reboots where it is: its clock starts again near 0, its EKF has no origin until its GPS is back
  LocalPositionReport none = placed(100'000, here, kFirstOrigin, 0);
  none.xy_global = false;
  const auto lost = f.onLocalPosition(none);
  ASSERT_TRUE(lost);
  EXPECT_FALSE(lost->valid);
  // AND then sets its origin where it rebooted (x, y = 0)
  f.onGps({2'000'000, kGpsFix3d});
  const auto g = f.onLocalPosition(placed(2'050'000, here, here, 2'000'000));
  // THEN the clock restart counts as before, the fix on the new clock is valid, and it is still where it was in the
  // first origin's frame
  ASSERT_TRUE(g);
  EXPECT_TRUE(g->valid);
  EXPECT_EQ(g->stamp_ns, 2'050'000'000);
  EXPECT_EQ(f.counters().clock_restarts, 1u);
  EXPECT_EQ(f.counters().origin_changes, 1u);
  EXPECT_LT((g->position_m - agent::Vec2(-80.0, 120.0)).norm(), 1e-6);
}

TEST(GnssForward, WithoutAGlobalReferenceXAndYPassAsBefore) {
  // GIVEN a PX4 whose local position never had a global reference (xy_global false throughout: no GPS origin yet)
  GnssForward f;
  f.onGps({0, kGpsFix3d});
  LocalPositionReport r = position(100'000, true, 3.0, -4.0);
  r.ref_lat_deg = kNaN;
  const auto g = f.onLocalPosition(r);
  // THEN its frame is forwarded as it is, as before issue #46, and nothing is counted against it
  ASSERT_TRUE(g && g->valid);
  EXPECT_EQ(g->position_m.x(), -4.0);
  EXPECT_EQ(g->position_m.y(), 3.0);
  EXPECT_EQ(f.counters().unusable_reference, 0u);
  EXPECT_TRUE(f.takeEvents().empty());
}

}  // namespace
}  // namespace swa::px4::gnss_test

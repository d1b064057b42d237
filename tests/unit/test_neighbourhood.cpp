// Neighbourhood rules on exact geometries (DESIGN §3.2): Gabriel keeps exactly the lattice edges, k nearest keeps
// the k nearest.

#include <algorithm>
#include <cmath>
#include <set>
#include <vector>

#include <gtest/gtest.h>

#include "swa/agent/neighbourhood.h"

namespace swa::agent {
namespace {

constexpr double kLatticeR = 10.0;
constexpr double kRange = 40.0;
constexpr double kNoCap = 1e6;  // Gabriel's test alone, no edge-length cap

Track track(int id, const Vec2& p, bool confirmed = true) {
  Track t;
  t.id = id;
  t.confirmed = confirmed;
  t.estimate.x.setZero();
  segment<pva::Pos>(t.estimate.x) = p;
  return t;
}

Vec2 polar(double d, double deg) {
  const double a = deg * M_PI / 180.0;
  return d * Vec2(std::cos(a), std::sin(a));
}

std::set<int> ids(const Neighbourhood& nb) { return {nb.ids.begin(), nb.ids.begin() + nb.count()}; }

// The focal UAV at a node of a triangular lattice of spacing r (rotated by `rot_deg`): tracks for every other node
// within 2.1 r — 6 at r (ids 0-5), 6 at sqrt(3) r (ids 10-15), 6 at 2 r (ids 20-25).
std::vector<Track> triangularLattice(double rot_deg) {
  std::vector<Track> t;
  for (int k = 0; k < 6; ++k) {
    t.push_back(track(k, polar(kLatticeR, rot_deg + 60.0 * k)));
    t.push_back(track(10 + k, polar(std::sqrt(3.0) * kLatticeR, rot_deg + 30.0 + 60.0 * k)));
    t.push_back(track(20 + k, polar(2.0 * kLatticeR, rot_deg + 60.0 * k)));
  }
  return t;
}

TEST(Gabriel, TriangularLatticeGivesExactlyTheSixLatticeEdges) {
  for (double rot : {0.0, 17.0, 45.0, 133.3}) {
    SCOPED_TRACE(rot);
    // GIVEN the 18 nearest lattice nodes around the focal UAV, first shell at r
    const std::vector<Track> tracks = triangularLattice(rot);
    // WHEN selecting by Gabriel's test alone
    const Neighbourhood nb = selectGabriel(tracks, kRange, kNoCap);
    // THEN the neighbours are the six first-shell nodes, nearest first: every second-shell node at sqrt(3) r has two
    // first-shell nodes inside its disc, every node at 2 r has one on its diameter
    EXPECT_EQ(ids(nb), (std::set<int>{0, 1, 2, 3, 4, 5}));
    for (int i = 0; i < nb.count(); ++i) EXPECT_NEAR(nb.positions.position[i].norm(), kLatticeR, 1e-9);
  }
}

TEST(Gabriel, SquareLatticeHasNoDiagonals) {
  // GIVEN a square lattice of spacing r: 4 sides at r, 4 diagonals at sqrt(2) r (each with two side nodes exactly on
  // its circle), rotated so no coordinate is exact
  for (double rot : {0.0, 30.0, 71.0}) {
    SCOPED_TRACE(rot);
    std::vector<Track> tracks;
    for (int k = 0; k < 4; ++k) {
      tracks.push_back(track(k, polar(kLatticeR, rot + 90.0 * k)));
      tracks.push_back(track(10 + k, polar(std::sqrt(2.0) * kLatticeR, rot + 45.0 + 90.0 * k)));
    }
    // WHEN selecting THEN only the four sides: a witness on the circle blocks (the closed disc of Gabriel's graph)
    EXPECT_EQ(ids(selectGabriel(tracks, kRange, kNoCap)), (std::set<int>{0, 1, 2, 3}));
  }
}

TEST(Gabriel, WitnessJustOutsideTheCircleDoesNotBlock) {
  // GIVEN j at (2r, 0) and m just outside the circle with diameter self-j (centre (r, 0), radius r)
  const std::vector<Track> tracks = {track(1, Vec2(2 * kLatticeR, 0)), track(2, Vec2(kLatticeR, 1.001 * kLatticeR))};
  // THEN both are neighbours; moved just inside, m blocks j
  EXPECT_EQ(ids(selectGabriel(tracks, kRange, kNoCap)), (std::set<int>{1, 2}));
  const std::vector<Track> inside = {track(1, Vec2(2 * kLatticeR, 0)), track(2, Vec2(kLatticeR, 0.999 * kLatticeR))};
  EXPECT_EQ(ids(selectGabriel(inside, kRange, kNoCap)), (std::set<int>{2}));
}

TEST(Gabriel, CollinearKeepsOnlyTheNearestOnEachSide) {
  // GIVEN five UAVs on a line through self: two ahead, three behind
  const std::vector<Track> tracks = {track(1, Vec2(10, 0)), track(2, Vec2(20, 0)), track(3, Vec2(-9, 0)),
                                     track(4, Vec2(-19, 0)), track(5, Vec2(-30, 0))};
  // THEN the nearest ahead and the nearest behind
  const Neighbourhood nb = selectGabriel(tracks, kRange, kNoCap);
  ASSERT_EQ(nb.count(), 2);
  EXPECT_EQ(nb.ids[0], 3);  // nearest first
  EXPECT_EQ(nb.ids[1], 1);
}

TEST(Gabriel, OneAndTwoTracks) {
  // GIVEN one track far away THEN it is the neighbour (the nearest always passes, whatever the cap)
  EXPECT_EQ(ids(selectGabriel({track(7, Vec2(0, 30))}, kRange, 15.0)), (std::set<int>{7}));
  // GIVEN two tracks on opposite sides THEN both
  EXPECT_EQ(ids(selectGabriel({track(7, Vec2(0, 10)), track(8, Vec2(0, -12))}, kRange, 15.0)), (std::set<int>{7, 8}));
  // GIVEN two tracks where the nearer sits inside the other's disc THEN only the nearer
  EXPECT_EQ(ids(selectGabriel({track(7, Vec2(10, 0)), track(8, Vec2(15, 2))}, kRange, kNoCap)), (std::set<int>{7}));
  // GIVEN no confirmed track THEN none
  EXPECT_EQ(selectGabriel({track(7, Vec2(10, 0), false)}, kRange, kNoCap).count(), 0);
  EXPECT_EQ(selectGabriel({}, kRange, kNoCap).count(), 0);
}

TEST(Gabriel, HiddenMiddleUavsAreCoveredByTheEdgeCap) {
  // GIVEN a lattice in which first-shell nodes 0 and 1 (at r, 0 and 60 deg) are untracked (a blind sector of the
  // field of view, missed detections), so nothing blocks second-shell node 10 at sqrt(3) r, 30 deg, behind them
  std::vector<Track> tracks = triangularLattice(0.0);
  tracks.erase(std::remove_if(tracks.begin(), tracks.end(), [](const Track& t) { return t.id == 0 || t.id == 1; }),
               tracks.end());
  // WHEN Gabriel's test alone decides THEN node 10 passes, and the fit would pull it to r (a 42 % squeeze)
  EXPECT_EQ(ids(selectGabriel(tracks, kRange, kNoCap)), (std::set<int>{2, 3, 4, 5, 10}));
  // WHEN the default cap of 1.3 r applies THEN only the four tracked first-shell nodes remain
  const FormationConfig defaults;
  EXPECT_DOUBLE_EQ(defaults.max_edge_factor, 1.3);
  EXPECT_EQ(ids(selectGabriel(tracks, kRange, defaults.max_edge_factor * kLatticeR)), (std::set<int>{2, 3, 4, 5}));
}

TEST(Gabriel, NearestPassesWhateverItsLength) {
  // GIVEN only a far UAV at 2 r behind an untracked one THEN it is kept: with one track it is the only reference
  EXPECT_EQ(ids(selectGabriel({track(3, Vec2(2 * kLatticeR, 0))}, kRange, 1.5 * kLatticeR)), (std::set<int>{3}));
}

TEST(Gabriel, TentativeTracksAndTracksBeyondRangeAreNotNeighbours) {
  // GIVEN a tentative track at r and a confirmed one beyond sensing range
  const std::vector<Track> tracks = {track(1, Vec2(10, 0), false), track(2, Vec2(-41, 0)), track(3, Vec2(0, 12))};
  // THEN only the confirmed one in range
  EXPECT_EQ(ids(selectGabriel(tracks, kRange, kNoCap)), (std::set<int>{3}));
}

TEST(Gabriel, ConfirmedTrackBeyondRangeStillBlocks) {
  // GIVEN j at 39 m and a witness on its diameter at 20 m, with sensing range 30 m: j is beyond range anyway; with
  // range 40 m the witness is a neighbour and blocks j
  const std::vector<Track> tracks = {track(1, Vec2(39, 0)), track(2, Vec2(20, 0))};
  EXPECT_EQ(ids(selectGabriel(tracks, 40.0, kNoCap)), (std::set<int>{2}));
}

TEST(Gabriel, TiesAreBrokenByIdWhateverTheTrackOrder) {
  // GIVEN two tracks at the same distance listed in either order
  const std::vector<Track> a = {track(4, Vec2(10, 0)), track(2, Vec2(-10, 0))};
  const std::vector<Track> b = {track(2, Vec2(-10, 0)), track(4, Vec2(10, 0))};
  // THEN the same neighbourhood in the same order
  const Neighbourhood na = selectGabriel(a, kRange, kNoCap), nbb = selectGabriel(b, kRange, kNoCap);
  ASSERT_EQ(na.count(), 2);
  EXPECT_EQ(na.ids[0], 2);
  EXPECT_EQ(nbb.ids[0], 2);
  EXPECT_EQ(na.ids[1], nbb.ids[1]);
}

TEST(Gabriel, ManyTracksAreCappedAtTheNeighbourLimit) {
  // GIVEN 40 tracks on a circle of r (every one passes: the circle's points are all outside each other's discs)
  std::vector<Track> tracks;
  for (int k = 0; k < 40; ++k) tracks.push_back(track(k, polar(kLatticeR, 9.0 * k)));
  // THEN at most kMaxNeighbours are returned
  EXPECT_EQ(selectGabriel(tracks, kRange, kNoCap).count(), kMaxNeighbours);
}

TEST(KNearest, KeepsTheKNearestConfirmedInRange) {
  const std::vector<Track> tracks = triangularLattice(0.0);
  // k = 3 on the lattice: three first-shell nodes (ties by id)
  const Neighbourhood nb = selectKNearest(tracks, 3, kRange);
  EXPECT_EQ(ids(nb), (std::set<int>{0, 1, 2}));
  // k = 8: the six first-shell nodes and two of the (equidistant up to rounding) second-shell nodes
  const std::set<int> eight = ids(selectKNearest(tracks, 8, kRange));
  ASSERT_EQ(eight.size(), 8u);
  for (int id = 0; id < 6; ++id) EXPECT_EQ(eight.count(id), 1u) << id;
  EXPECT_EQ(std::count_if(eight.begin(), eight.end(), [](int id) { return id >= 10 && id < 16; }), 2);
}

TEST(SelectNeighbours, DispatchesOnTheConfiguredRule) {
  const std::vector<Track> tracks = triangularLattice(10.0);
  FormationConfig f;
  f.neighbourhood = NeighbourhoodRule::kGabriel;
  EXPECT_EQ(selectNeighbours(tracks, f).count(), 6);
  f.neighbourhood = NeighbourhoodRule::kKNearest;
  f.k = 2;
  EXPECT_EQ(selectNeighbours(tracks, f).count(), 2);
}

TEST(Neighbourhood, ARankedFrameChangesWhenTheTwoNearestDoWithinTheSameSet) {
  // GIVEN three neighbours, then the same three with the third and the second nearest swapped, then the first two
  // swapped with each other
  std::vector<Track> t{track(1, polar(9.8, 0.0)), track(2, polar(10.0, 120.0)), track(3, polar(10.2, 240.0))};
  const Neighbourhood before = selectGabriel(t, kRange, kNoCap);
  t[2] = track(3, polar(9.9, 240.0));
  const Neighbourhood third_in = selectGabriel(t, kRange, kNoCap);
  t[0] = track(1, polar(9.95, 0.0));
  const Neighbourhood first_two_swapped = selectGabriel(t, kRange, kNoCap);
  // THEN unranked (set only) all three are the same frame; ranked (the weighted fit) the one that lets 3 into the
  // nearest two is another frame, the swap of the two nearest is not
  ASSERT_EQ(before.count(), 3);
  EXPECT_TRUE(before.sameFrameAs(third_in, false));
  EXPECT_FALSE(before.sameFrameAs(third_in, true));
  EXPECT_TRUE(third_in.sameFrameAs(first_two_swapped, true));
  EXPECT_EQ(first_two_swapped.ids[0], 3);
  // AND with two neighbours the order never matters
  const std::vector<Track> two{track(1, polar(9.8, 0.0)), track(2, polar(10.0, 120.0))};
  const std::vector<Track> two_swapped{track(1, polar(10.1, 0.0)), track(2, polar(10.0, 120.0))};
  EXPECT_TRUE(selectGabriel(two, kRange, kNoCap).sameFrameAs(selectGabriel(two_swapped, kRange, kNoCap), true));
}

TEST(Neighbourhood, CarriesEachNeighboursTrackCovarianceInItsOrder) {
  std::vector<Track> t{track(1, polar(12.0, 0.0)), track(2, polar(10.0, 120.0))};
  t[0].estimate.P.setIdentity();
  t[1].estimate.P = 2.0 * PvaMat::Identity();
  const Neighbourhood nb = selectGabriel(t, kRange, kNoCap);
  ASSERT_EQ(nb.count(), 2);
  EXPECT_EQ(nb.ids[0], 2);
  EXPECT_EQ(nb.covariances[0], 2.0 * Mat2::Identity());
  EXPECT_EQ(nb.covariances[1], Mat2::Identity());
}

}  // namespace
}  // namespace swa::agent

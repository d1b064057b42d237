// Per-step swarm geometry against hand-computed configurations.

#include <cmath>
#include <initializer_list>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "swa/monitor/swarm_metrics.h"

namespace swa::monitor {
namespace {

using agent::Vec2;

std::vector<UavTruth> swarm(const std::vector<Vec2>& positions) {
  std::vector<UavTruth> uavs;
  int id = 0;
  for (const Vec2& p : positions) uavs.push_back({id++, p, Vec2::Zero(), true});
  return uavs;
}

// Equilateral triangle of side `side`, first corner at `origin`.
std::vector<UavTruth> equilateral(double side, const Vec2& origin = Vec2::Zero()) {
  return swarm({origin, origin + Vec2(side, 0.0), origin + Vec2(0.5 * side, 0.5 * std::sqrt(3.0) * side)});
}

TEST(MetricsGeometry, EquilateralTriangleOfSideRIsAPerfectSingleGroup) {
  // GIVEN 3 UAVs in an equilateral triangle of side 10 m = r
  const MetricsConfig config;
  // WHEN the geometry is computed
  const Geometry g = computeGeometry(equilateral(10.0, Vec2(3.0, -2.0)), config);
  // THEN every UAV's two nearest others are 10 m away, there is one group and the formation error is zero
  EXPECT_EQ(g.uav_count, 3);
  EXPECT_NEAR(g.mean_neighbor_distance_m, 10.0, 1e-12);
  EXPECT_NEAR(g.min_separation_m, 10.0, 1e-12);
  EXPECT_EQ(g.groups, 1);
  EXPECT_NEAR(g.formation_error_m, 0.0, 1e-12);
  EXPECT_NEAR(g.edge_length_m, 10.0, 1e-12);  // all three sides are Gabriel edges
  // AND the centroid is the triangle's centre, 10/sqrt(3) m from each corner
  EXPECT_NEAR(g.centroid_m.x(), 3.0 + 5.0, 1e-12);
  EXPECT_NEAR(g.centroid_m.y(), -2.0 + 5.0 / std::sqrt(3.0), 1e-12);
  EXPECT_NEAR(g.spread_m, 10.0 / std::sqrt(3.0), 1e-12);
}

TEST(MetricsGeometry, UnevenLineShowsFormationErrorThatDnbHides) {
  // GIVEN UAVs on a line at x = 0, 8, 20 and r = 10
  const Geometry g = computeGeometry(swarm({Vec2(0, 0), Vec2(8, 0), Vec2(20, 0)}), MetricsConfig{});
  // THEN (hand computed) per-UAV nearest-two means are 14, 10, 16 -> d_NB = 40/3
  EXPECT_NEAR(g.mean_neighbor_distance_m, 40.0 / 3.0, 1e-12);
  // AND the per-UAV mean |d - r| over the same pairs are (2+10)/2, (2+2)/2, (2+10)/2 -> 14/3: the middle UAV has a
  // d_NB of exactly r but still a 2 m error, and the error bounds |d_NB - r| from above
  EXPECT_NEAR(g.formation_error_m, 14.0 / 3.0, 1e-12);
  EXPECT_GE(g.formation_error_m, std::fabs(g.mean_neighbor_distance_m - 10.0));
  EXPECT_NEAR(g.min_separation_m, 8.0, 1e-12);
  // AND the Gabriel edges are the two links of the chain (the middle UAV blocks 0-20): (8 + 12) / 2
  EXPECT_NEAR(g.edge_length_m, 10.0, 1e-12);
  // AND the chain 0-8-20 (links 8 and 12 < 15) is one group although the ends are 20 m apart
  EXPECT_EQ(g.groups, 1);
  EXPECT_NEAR(g.centroid_m.x(), 28.0 / 3.0, 1e-12);
  EXPECT_NEAR(g.spread_m, 20.0 - 28.0 / 3.0, 1e-12);
}

TEST(MetricsGeometry, EdgeLengthReadsTheSpacingWhereDnbReadsLow) {
  // GIVEN a centre UAV with six neighbours at 60 deg steps, alternately 9 m and 11 m away (mean spacing 10 m)
  std::vector<Vec2> p{Vec2::Zero()};
  for (int k = 0; k < 6; ++k) {
    const double a = k * M_PI / 3.0;
    p.push_back((k % 2 == 0 ? 11.0 : 9.0) * Vec2(std::cos(a), std::sin(a)));
  }
  const Geometry g = computeGeometry(swarm(p), MetricsConfig{});
  // THEN (hand computed) the Gabriel graph is the six spokes and the six ring sides of sqrt(9^2 + 11^2 - 99) m,
  // mean (3*9 + 3*11 + 6*sqrt(103)) / 12 = 10.07 m ...
  const double side = std::sqrt(103.0);
  EXPECT_NEAR(g.edge_length_m, (60.0 + 6.0 * side) / 12.0, 1e-12);
  // ... while d_NB takes each UAV's two nearest: 9 for the centre, (9 + side) / 2 and side for the ring, 9.74 m
  EXPECT_NEAR(g.mean_neighbor_distance_m, (9.0 + 1.5 * (9.0 + side) + 3.0 * side) / 7.0, 1e-12);
  EXPECT_LT(g.mean_neighbor_distance_m, 9.75);
}

TEST(MetricsGeometry, TriangularLatticeEdgesAreTheSpacing) {
  // GIVEN 19 UAVs on a hexagonal patch of a triangular lattice of spacing 10 m
  std::vector<Vec2> lattice;
  for (int i = -2; i <= 2; ++i) {
    for (int j = -2; j <= 2; ++j) {
      if (std::abs(i + j) <= 2) lattice.push_back(10.0 * Vec2(i + 0.5 * j, 0.5 * std::sqrt(3.0) * j));
    }
  }
  ASSERT_EQ(lattice.size(), 19u);
  // THEN every Gabriel edge is a lattice edge of 10 m
  EXPECT_NEAR(computeGeometry(swarm(lattice), MetricsConfig{}).edge_length_m, 10.0, 1e-9);
}

TEST(MetricsGeometry, SquareHasNoDiagonalEdges) {
  // GIVEN 4 UAVs on a 10 m square: each diagonal has the other two corners on its circle
  const Geometry g = computeGeometry(swarm({Vec2(0, 0), Vec2(10, 0), Vec2(10, 10), Vec2(0, 10)}), MetricsConfig{});
  // THEN the edges are the four sides only
  EXPECT_NEAR(g.edge_length_m, 10.0, 1e-12);
  EXPECT_NEAR(meanGabrielEdgeLength({Vec2(0, 0), Vec2(3, 4)}), 5.0, 1e-12);
  EXPECT_TRUE(std::isnan(meanGabrielEdgeLength({Vec2(1, 1)})));
}

TEST(MetricsGeometry, TwoClustersFarApartAreTwoGroups) {
  // GIVEN two triangles of side 10 m whose centres are 100 m apart
  std::vector<UavTruth> uavs = equilateral(10.0);
  for (UavTruth u : equilateral(10.0, Vec2(100.0, 0.0))) {
    u.id += 3;
    uavs.push_back(u);
  }
  const Geometry g = computeGeometry(uavs, MetricsConfig{});
  // THEN two groups and d_NB still 10 m; the centroid is (55, 5/sqrt(3)) and the farthest UAVs are the corners on
  // y = 0 at x = 0 and x = 110
  EXPECT_EQ(g.groups, 2);
  EXPECT_NEAR(g.mean_neighbor_distance_m, 10.0, 1e-12);
  EXPECT_NEAR(g.min_separation_m, 10.0, 1e-12);
  EXPECT_NEAR(g.centroid_m.x(), 55.0, 1e-12);
  EXPECT_NEAR(g.centroid_m.y(), 5.0 / std::sqrt(3.0), 1e-12);
  EXPECT_NEAR(g.spread_m, std::sqrt(55.0 * 55.0 + 25.0 / 3.0), 1e-12);
}

TEST(MetricsGeometry, GroupLinkIsStrictlyCloserThanOneAndAHalfR) {
  // GIVEN r = 10: the link distance is 15 m
  const MetricsConfig config;
  EXPECT_EQ(computeGeometry(swarm({Vec2(0, 0), Vec2(15.0, 0)}), config).groups, 2);
  EXPECT_EQ(computeGeometry(swarm({Vec2(0, 0), Vec2(14.999, 0)}), config).groups, 1);
  // AND with r = 20 the same 15 m pair is linked
  MetricsConfig wide;
  wide.formation.radius_m = 20.0;
  EXPECT_EQ(computeGeometry(swarm({Vec2(0, 0), Vec2(15.0, 0)}), wide).groups, 1);
}

TEST(MetricsGeometry, CountGroupsFindsEveryComponent) {
  // GIVEN isolated points, a pair and a chain of three
  const std::vector<Vec2> p{Vec2(0, 0),   Vec2(100, 0), Vec2(101, 0),  Vec2(0, 100),
                            Vec2(0, 104), Vec2(0, 108), Vec2(-50, -50)};
  // THEN with a 5 m link: {0}, {1,2}, {3,4,5}, {6}
  EXPECT_EQ(countGroups(p, 5.0), 4);
  EXPECT_EQ(countGroups(p, 0.5), 7);
  EXPECT_EQ(countGroups(p, 1e4), 1);
  EXPECT_EQ(countGroups({}, 5.0), 0);
}

TEST(MetricsGeometry, TwoUavsUseTheOneOther) {
  // GIVEN N = 2, 12 m apart
  const Geometry g = computeGeometry(swarm({Vec2(0, 0), Vec2(0, 12)}), MetricsConfig{});
  // THEN d_NB is their distance and the formation error its offset from r
  EXPECT_NEAR(g.mean_neighbor_distance_m, 12.0, 1e-12);
  EXPECT_NEAR(g.formation_error_m, 2.0, 1e-12);
  EXPECT_NEAR(g.min_separation_m, 12.0, 1e-12);
  EXPECT_NEAR(g.spread_m, 6.0, 1e-12);
}

TEST(MetricsGeometry, DistanceNeighboursIsAParameter) {
  // GIVEN a square of side 10 (diagonal 14.14)
  const auto square = swarm({Vec2(0, 0), Vec2(10, 0), Vec2(10, 10), Vec2(0, 10)});
  MetricsConfig c;
  // THEN with the two nearest the square is perfect, with three the diagonal enters
  EXPECT_NEAR(computeGeometry(square, c).mean_neighbor_distance_m, 10.0, 1e-12);
  c.distance_neighbours = 3;
  EXPECT_NEAR(computeGeometry(square, c).mean_neighbor_distance_m, (20.0 + 10.0 * std::sqrt(2.0)) / 3.0, 1e-12);
  EXPECT_NEAR(computeGeometry(square, c).formation_error_m, (10.0 * std::sqrt(2.0) - 10.0) / 3.0, 1e-12);
}

TEST(MetricsGeometry, DeadAndNonFiniteUavsAreLeftOut) {
  // GIVEN a triangle plus one dead UAV on top of corner 0 and one with a NaN position
  std::vector<UavTruth> uavs = equilateral(10.0);
  uavs.push_back({7, Vec2(0.1, 0.0), Vec2::Zero(), false});
  uavs.push_back({8, Vec2(std::nan(""), 0.0), Vec2::Zero(), true});
  const Geometry g = computeGeometry(uavs, MetricsConfig{});
  // THEN the metrics are those of the triangle alone
  EXPECT_EQ(g.uav_count, 3);
  EXPECT_NEAR(g.min_separation_m, 10.0, 1e-12);
  EXPECT_NEAR(g.mean_neighbor_distance_m, 10.0, 1e-12);
  EXPECT_EQ(g.groups, 1);
}

TEST(MetricsGeometry, UndefinedValuesAreNaNNotZero) {
  // GIVEN one UAV
  const Geometry one = computeGeometry(swarm({Vec2(4, 5)}), MetricsConfig{});
  // THEN it is one group of spread 0, with no distance-based metric
  EXPECT_EQ(one.groups, 1);
  EXPECT_DOUBLE_EQ(one.spread_m, 0.0);
  EXPECT_DOUBLE_EQ(one.centroid_m.x(), 4.0);
  EXPECT_TRUE(std::isnan(one.mean_neighbor_distance_m));
  EXPECT_TRUE(std::isnan(one.min_separation_m));
  EXPECT_TRUE(std::isnan(one.formation_error_m));
  // AND no UAV at all has no groups and no centroid
  const Geometry none = computeGeometry({}, MetricsConfig{});
  EXPECT_EQ(none.uav_count, 0);
  EXPECT_EQ(none.groups, 0);
  EXPECT_TRUE(std::isnan(none.centroid_m.x()));
  EXPECT_TRUE(std::isnan(none.spread_m));
}

TEST(MetricsGeometry, ConfigValidationReportsEveryProblem) {
  MetricsConfig c;
  EXPECT_NO_THROW(validate(c));
  c.collision_distance_m = 0.0;
  c.distance_neighbours = 0;
  c.anees_alpha = 1.0;
  try {
    validate(c);
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("collision_distance_m"), std::string::npos);
    EXPECT_NE(what.find("distance_neighbours"), std::string::npos);
    EXPECT_NE(what.find("anees_alpha"), std::string::npos);
  }
}

}  // namespace
}  // namespace swa::monitor

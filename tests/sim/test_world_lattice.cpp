// Initial placement: hexagonal lattice slots filled ring by ring, jitter, headings.
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "swa/sim/lattice.h"
#include "swa/sim/world.h"

namespace swa::sim {
namespace {

using agent::Vec2;

double nearestNeighbourDistance(const std::vector<Vec2>& points, std::size_t i) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t j = 0; j < points.size(); ++j) {
    if (j != i) best = std::min(best, (points[i] - points[j]).norm());
  }
  return best;
}

double maxRadius(const std::vector<Vec2>& points) {
  double r = 0.0;
  for (const Vec2& p : points) r = std::max(r, p.norm());
  return r;
}

TEST(WorldLattice, EveryUavHasANeighbourAtExactlyTheSpacingAndNoneCloser) {
  for (int n = 2; n <= 32; ++n) {
    // GIVEN n slots at 10 m spacing
    const std::vector<Vec2> slots = hexLattice(n, 10.0);
    ASSERT_EQ(slots.size(), static_cast<std::size_t>(n));
    // THEN each slot's nearest neighbour is exactly 10 m away
    for (std::size_t i = 0; i < slots.size(); ++i) {
      EXPECT_NEAR(nearestNeighbourDistance(slots, i), 10.0, 1e-9) << "n=" << n << " slot " << i;
    }
  }
}

TEST(WorldLattice, FillsRingsAroundTheOrigin) {
  // GIVEN the centred hexagonal numbers 1, 7, 19, 37 (complete rings)
  // THEN the cluster radius is exactly 0, 1, 2, 3 spacings
  EXPECT_NEAR(maxRadius(hexLattice(1, 10.0)), 0.0, 1e-12);
  EXPECT_NEAR(maxRadius(hexLattice(7, 10.0)), 10.0, 1e-9);
  EXPECT_NEAR(maxRadius(hexLattice(19, 10.0)), 20.0, 1e-9);
  EXPECT_NEAR(maxRadius(hexLattice(37, 10.0)), 30.0, 1e-9);
  // AND slot 0 is the origin, slot 1 straight east (the MPS tests rely on it)
  const std::vector<Vec2> two = hexLattice(2, 10.0);
  EXPECT_NEAR(two[0].norm(), 0.0, 1e-12);
  EXPECT_NEAR(two[1].x(), 10.0, 1e-12);
  EXPECT_NEAR(two[1].y(), 0.0, 1e-12);
}

TEST(WorldLattice, ClusterIsAsCompactAsTheLatticeAllows) {
  for (int n = 1; n <= 32; ++n) {
    const std::vector<Vec2> slots = hexLattice(n, 1.0);
    // THEN no unused lattice point is strictly closer to the origin than the farthest used one
    const double used = maxRadius(slots);
    const std::vector<Vec2> more = hexLattice(n + 40, 1.0);
    for (std::size_t k = static_cast<std::size_t>(n); k < more.size(); ++k) {
      EXPECT_GE(more[k].norm(), used - 1e-9) << "n=" << n;
    }
    // AND the radius is close to that of a disc holding n points at the lattice density (area sqrt(3)/2 per point)
    const double disc = std::sqrt(static_cast<double>(n) * std::sqrt(3.0) / (2.0 * M_PI));
    EXPECT_LE(used, disc + 1.0) << "n=" << n;
    // AND the centroid stays within one spacing of the origin
    Vec2 centroid = Vec2::Zero();
    for (const Vec2& p : slots) centroid += p / static_cast<double>(n);
    EXPECT_LT(centroid.norm(), 1.0) << "n=" << n;
  }
}

TEST(WorldLattice, WorldPlacesUavsWithinJitterOfTheirSlotsAtRest) {
  double displacement_sum = 0.0;
  int count = 0;
  for (int n = 1; n <= 32; ++n) {
    // GIVEN a world of n UAVs at 10 m spacing with 1 m jitter
    Scenario s;
    s.uav_count = n;
    s.seed = 42;
    s.formation.spacing_m = 10.0;
    s.formation.position_jitter_m = 1.0;
    const World world(s);
    const std::vector<Vec2> slots = hexLattice(n, 10.0);
    std::vector<Vec2> placed;
    for (const UavTruth& t : world.truth()) {
      // THEN every UAV is within the jitter of its slot, at rest
      const double d = (t.position_m - slots[static_cast<std::size_t>(t.id)]).norm();
      EXPECT_LE(d, 1.0);
      displacement_sum += d;
      ++count;
      EXPECT_EQ(t.velocity_mps, Vec2::Zero());
      placed.push_back(t.position_m);
    }
    // AND nearest neighbours are at the spacing +- twice the jitter
    for (std::size_t i = 0; n > 1 && i < placed.size(); ++i) {
      const double nn = nearestNeighbourDistance(placed, i);
      EXPECT_GE(nn, 8.0);
      EXPECT_LE(nn, 12.0);
    }
  }
  // AND the jitter is uniform in the disc: mean displacement 2/3 of the radius (528 UAVs, std of mean ~0.01 m)
  EXPECT_NEAR(displacement_sum / count, 2.0 / 3.0, 0.05);
}

TEST(WorldLattice, HeadingsAreRandomOrZeroAndTurnAtConstantRate) {
  // GIVEN 32 UAVs with random headings
  Scenario s;
  s.uav_count = 32;
  s.seed = 3;
  const World random_world(s);
  double mean_cos = 0.0, mean_sin = 0.0;
  for (const UavTruth& t : random_world.truth()) {
    EXPECT_GT(t.heading_rad, -M_PI);
    EXPECT_LE(t.heading_rad, M_PI);
    mean_cos += std::cos(t.heading_rad) / 32.0;
    mean_sin += std::sin(t.heading_rad) / 32.0;
  }
  // THEN they are spread around the circle (mean resultant length of 32 uniform angles ~ 0.16)
  EXPECT_LT(std::hypot(mean_cos, mean_sin), 0.45);

  // GIVEN 256 UAVs with zero headings and a turn-rate spread of 0.1 rad/s
  s.uav_count = 256;
  s.dynamics.heading = HeadingMode::kZero;
  s.dynamics.heading_rate_std_radps = 0.1;
  s.gnss.dropout_start_s = 0.0;
  World turning(s);
  for (const UavTruth& t : turning.truth()) EXPECT_EQ(t.heading_rad, 0.0);
  for (int k = 0; k < 100; ++k) turning.step();
  const std::vector<UavTruth> at1 = turning.truth();
  for (int k = 0; k < 100; ++k) turning.step();
  // THEN each heading grows linearly: psi(2 s) = 2 psi(1 s) (rates of 0.1 rad/s keep it inside (-pi, pi])
  double spread = 0.0;
  for (std::size_t i = 0; i < at1.size(); ++i) {
    EXPECT_NEAR(turning.truth()[i].heading_rad, 2.0 * at1[i].heading_rad, 1e-12);
    spread += at1[i].heading_rad * at1[i].heading_rad / 256.0;
  }
  // AND the rates have the configured std (256 draws: relative std of the estimate ~4 %)
  EXPECT_NEAR(std::sqrt(spread), 0.1, 0.012);
}

}  // namespace
}  // namespace swa::sim

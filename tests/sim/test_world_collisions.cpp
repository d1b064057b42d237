// Collisions: counted once per onset, the UAVs are left where they are.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "swa/sim/world.h"
#include "world_support.h"

namespace swa::sim {
namespace {

using agent::Vec2;

// UAV 0 hovers at the origin, UAV 1 starts 10 m east; no wind, no jitter.
Scenario twoUavs() { return testing::calmScenario(2, 13); }

// Flies UAV 1 to x = target with a P loop for `seconds`; collects collision events.
void flyUav1To(World& world, double target_x, double seconds, std::vector<Event>& collisions) {
  for (int k = 0; k < static_cast<int>(seconds * 100); ++k) {
    agent::VelocityCommand hold, go;
    go.velocity_mps = Vec2(1.5 * (target_x - world.truth()[1].position_m.x()), 0.0);
    world.command(0, hold);
    world.command(1, go);
    world.step();
    for (const Event& e : world.events()) {
      if (e.kind == EventKind::kCollision) collisions.push_back(e);
    }
  }
}

TEST(WorldCollisions, FlyingThroughAnotherUavCountsOneCollisionPerPass) {
  World world(twoUavs());
  std::vector<Event> collisions;
  // WHEN UAV 1 flies through UAV 0 to the west side
  flyUav1To(world, -10.0, 20.0, collisions);
  // THEN one collision is counted, with its distance, and nobody was moved apart
  ASSERT_EQ(collisions.size(), 1u);
  EXPECT_EQ(world.collisions(), 1);
  EXPECT_EQ(collisions[0].uav, 0);
  EXPECT_EQ(collisions[0].other_uav, 1);
  EXPECT_LT(collisions[0].value, 1.5);
  EXPECT_GT(collisions[0].value, 1.4);  // at <= 2 m/s, the 10 ms step moves <= 2 cm past the threshold
  EXPECT_NEAR(world.truth()[1].position_m.x(), -10.0, 0.1);
  // WHEN it flies back east
  flyUav1To(world, 10.0, 20.0, collisions);
  // THEN that is a second onset
  EXPECT_EQ(world.collisions(), 2);
  EXPECT_EQ(collisions.size(), 2u);
}

TEST(WorldCollisions, LingeringNearTheThresholdIsOneCollisionUntilThePairSeparates) {
  World world(twoUavs());
  std::vector<Event> collisions;
  // WHEN UAV 1 closes to 1.2 m, backs off to 1.8 m, closes again
  flyUav1To(world, 1.2, 15.0, collisions);
  flyUav1To(world, 1.8, 10.0, collisions);
  ASSERT_NEAR(world.truth()[1].position_m.x(), 1.8, 0.01);
  flyUav1To(world, 1.2, 10.0, collisions);
  // THEN it is still one collision (contact ends only beyond 2 m)
  EXPECT_EQ(world.collisions(), 1);
  // WHEN it separates to 3 m and closes again
  flyUav1To(world, 3.0, 10.0, collisions);
  flyUav1To(world, 1.2, 10.0, collisions);
  // THEN that is a new collision
  EXPECT_EQ(world.collisions(), 2);
  EXPECT_EQ(collisions.size(), 2u);
}

TEST(WorldCollisions, UavsPlacedTooCloseCollideAtConstruction) {
  Scenario s = twoUavs();
  s.formation.spacing_m = 1.0;
  const World world(s);
  EXPECT_EQ(world.collisions(), 1);
  ASSERT_EQ(world.events().size(), 1u);
  EXPECT_EQ(world.events()[0].kind, EventKind::kCollision);
  EXPECT_EQ(world.events()[0].stamp_ns, 0);
  EXPECT_NEAR(world.events()[0].value, 1.0, 1e-12);
}

}  // namespace
}  // namespace swa::sim

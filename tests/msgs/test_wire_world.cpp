// The simulator's world topics: each type survives the DDS serialisation path, and ground truth, scenario events
// and clock ticks go through the wire bridge (swa/wire/world.h) and the wire and come back as sent.

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include <swa/msg/ClockPubSubTypes.h>
#include <swa/msg/ScenarioEventPubSubTypes.h>
#include <swa/msg/SwarmMetricsPubSubTypes.h>
#include <swa/msg/SwarmTruthPubSubTypes.h>

#include "roundtrip.h"
#include "swa/wire/world.h"

namespace swa::wire {
namespace {

using msg::test::make_header;
using msg::test::through_the_wire;

sim::UavTruth uav(int id, double base, bool gnss_valid) {
  sim::UavTruth u;
  u.id = id;
  u.position_m = agent::Vec2(base + 0.5, base + 1.0 / 3.0);
  u.velocity_mps = agent::Vec2(base + 2.5, base + 3.5);
  u.acceleration_mps2 = agent::Vec2(base + 4.5, base + 5.5);
  u.heading_rad = base * 0.01 + 0.125;
  u.gnss_valid = gnss_valid;
  return u;
}

TEST(WireMessages, WorldMessagesSurviveSerialisation) {
  // GIVEN one message of each world type, 64-bit fields beyond 32 bits, a negative (every-UAV) id
  const msg::SwarmTruth truth =
      toMsg(SwarmTruth{1'000'000'000, {uav(0, 10.0, true), uav(1, -20.0, false)}, {true, false}}, 100);
  msg::ScenarioEvent event;
  event.header(make_header(33'000'000'000, 4));
  event.kind(msg::EVENT_SCENARIO_END);
  event.uav_id(msg::ALL_UAVS);
  event.other_uav_id(-1);
  event.text("completed");
  const msg::Clock clock = toMsg(ClockTick{5'000'000'000ULL, 50'000'000'000'000, 10'000'000}, 5);
  msg::SwarmMetrics metrics;
  metrics.header(make_header(60'000'000'000, 600));
  metrics.mean_neighbor_distance_m(12.5);
  metrics.centroid_drift_mps(0.03125);
  metrics.min_separation_m(2.25);
  metrics.collisions(3);
  metrics.spread_m(48.75);
  metrics.groups(2);
  metrics.formation_error_m(1.5);
  metrics.anees_position(1.96);
  metrics.anees_velocity(2.04);
  metrics.anees_band_low(1.7);
  metrics.anees_band_high(2.3);
  metrics.live_agents(19);
  // WHEN each goes through serialize/deserialize THEN each copy equals its original, under its qualified type name
  const msg::SwarmTruth t = through_the_wire<msg::SwarmTruthPubSubType>(truth, "swa::msg::SwarmTruth");
  ASSERT_EQ(t.uavs().size(), 2u);
  EXPECT_FALSE(t.uavs()[1].alive());
  EXPECT_STREQ(msg::UavTruthPubSubType().getName(), "swa::msg::UavTruth");
  EXPECT_EQ(through_the_wire<msg::ScenarioEventPubSubType>(event, "swa::msg::ScenarioEvent").uav_id(), -1);
  EXPECT_EQ(through_the_wire<msg::ClockPubSubType>(clock, "swa::msg::Clock").step(), 5'000'000'000ULL);
  EXPECT_EQ(through_the_wire<msg::SwarmMetricsPubSubType>(metrics, "swa::msg::SwarmMetrics").groups(), 2u);
}

TEST(WireWorld, TruthSurvivesTheBridgeAndTheWire) {
  // GIVEN the truth of three UAVs, the middle one's agent not answering
  const SwarmTruth in{
      12'345'678'901, {uav(0, 1.0, true), uav(4, -7.0, false), uav(2, 1e-9, true)}, {true, false, true}};
  // WHEN it goes truth -> message -> wire -> message -> truth
  const SwarmTruth out = fromMsg(through_the_wire<msg::SwarmTruthPubSubType>(toMsg(in, 31), "swa::msg::SwarmTruth"));
  // THEN every carried field comes back bit for bit, in order
  EXPECT_EQ(out.stamp_ns, in.stamp_ns);
  EXPECT_EQ(out.agent_alive, in.agent_alive);
  ASSERT_EQ(out.uavs.size(), 3u);
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_EQ(out.uavs[k].id, in.uavs[k].id) << k;
    EXPECT_EQ(out.uavs[k].position_m, in.uavs[k].position_m) << k;
    EXPECT_EQ(out.uavs[k].velocity_mps, in.uavs[k].velocity_mps) << k;
    EXPECT_EQ(out.uavs[k].acceleration_mps2, in.uavs[k].acceleration_mps2) << k;
    EXPECT_EQ(out.uavs[k].heading_rad, in.uavs[k].heading_rad) << k;
    EXPECT_EQ(out.uavs[k].gnss_valid, in.uavs[k].gnss_valid) << k;
  }
  // AND an id no UAV can have is read as -1, never as a UAV index
  msg::SwarmTruth corrupt = toMsg(in, 32);
  corrupt.uavs()[0].id(std::numeric_limits<std::uint32_t>::max());
  EXPECT_EQ(fromMsg(corrupt).uavs[0].id, -1);
}

TEST(WireWorld, EveryEventKindSurvivesTheBridgeAndTheWire) {
  // GIVEN one event of each kind, at stamps up to a day of sim time (10 ms steps)
  namespace kind = sim::event_kind;
  int k = 0;
  for (const char* name :
       {kind::kGnssLost, kind::kGnssRestored, kind::kAgentDead, kind::kAgentRejoined, kind::kCollision, kind::kFailsafe,
        kind::kScenarioEnd, kind::kControlLost, kind::kControlRegained}) {
    for (const std::int64_t stamp_ns :
         {std::int64_t{0}, std::int64_t{10'000'000}, std::int64_t{12'340'000'000}, std::int64_t{86'399'990'000'000}}) {
      const sim::EventRecord in{static_cast<double>(stamp_ns) * 1e-9, name, k, k + 1, 0.1 * k,
                                "event " + std::to_string(k)};
      // WHEN it goes record -> message -> wire -> message -> record
      const msg::ScenarioEvent m = through_the_wire<msg::ScenarioEventPubSubType>(
          toMsg(in, static_cast<std::uint32_t>(k)), "swa::msg::ScenarioEvent");
      const std::optional<sim::EventRecord> out = fromMsg(m);
      // THEN the stamp is the event's time in nanoseconds, exactly, and every field comes back
      EXPECT_EQ(m.header().stamp_ns(), stamp_ns) << name;
      ASSERT_TRUE(out.has_value()) << name;
      EXPECT_EQ(out->t_s, in.t_s) << name;
      EXPECT_EQ(out->kind, in.kind);
      EXPECT_EQ(out->uav, in.uav);
      EXPECT_EQ(out->other_uav, in.other_uav);
      EXPECT_EQ(out->value, in.value);
      EXPECT_EQ(out->text, in.text);
    }
    ++k;
  }
  // AND a kind this build does not know is dropped by the reader, and one it does not define refused by the writer
  msg::ScenarioEvent unknown;
  unknown.kind(static_cast<msg::EventKind>(42));
  EXPECT_FALSE(fromMsg(unknown).has_value());
  EXPECT_THROW(toMsg(sim::EventRecord{1.0, "volcano", 0, -1, 0.0, ""}, 1), std::invalid_argument);
}

TEST(WireWorld, ClockTickSurvivesTheBridgeAndTheWire) {
  // GIVEN a tick whose 64-bit fields exceed 32 bits
  const ClockTick in{5'000'000'000ULL, 50'000'000'000'000, 10'000'000};
  // WHEN it goes tick -> message -> wire -> message -> tick
  const msg::Clock m = through_the_wire<msg::ClockPubSubType>(toMsg(in, 5), "swa::msg::Clock");
  const ClockTick out = fromMsg(m);
  // THEN it is the same tick, stamped with its sim time
  EXPECT_EQ(out.step, in.step);
  EXPECT_EQ(out.sim_time_ns, in.sim_time_ns);
  EXPECT_EQ(out.step_period_ns, in.step_period_ns);
  EXPECT_EQ(m.header().stamp_ns(), in.sim_time_ns);
}

}  // namespace
}  // namespace swa::wire

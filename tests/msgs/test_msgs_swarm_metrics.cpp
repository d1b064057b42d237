#include <swa/msg/SwarmMetricsPubSubTypes.h>

#include "roundtrip.h"

using namespace swa::msg;

TEST(MsgSwarmMetrics, TypeNameIsFullyQualified)
{
    EXPECT_STREQ(SwarmMetricsPubSubType().getName(), "swa::msg::SwarmMetrics");
}

TEST(MsgSwarmMetrics, RoundTripPreservesEveryField)
{
    // GIVEN metrics with every field set to a distinct non-default value
    SwarmMetrics in;
    in.header(test::make_header(60'000'000'000, 600));
    in.mean_neighbor_distance_m(12.5);
    in.centroid_drift_mps(0.03125);
    in.min_separation_m(2.25);
    in.collisions(3);
    in.spread_m(48.75);
    in.groups(2);
    in.formation_error_m(1.5);
    in.anees_position(1.96);
    in.anees_velocity(2.04);
    in.anees_band_low(1.7);
    in.anees_band_high(2.3);
    in.live_agents(19);

    // WHEN it goes through serialize/deserialize
    const auto out = test::round_trip<SwarmMetricsPubSubType>(in);

    // THEN the copy equals the original
    ASSERT_TRUE(out.has_value());
    EXPECT_TRUE(*out == in);
    EXPECT_EQ(out->groups(), 2u);
    EXPECT_DOUBLE_EQ(out->anees_band_high(), 2.3);
}

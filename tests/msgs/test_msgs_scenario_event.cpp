#include <swa/msg/ScenarioEventPubSubTypes.h>

#include "roundtrip.h"

using namespace swa::msg;

TEST(MsgScenarioEvent, TypeNameIsFullyQualified)
{
    EXPECT_STREQ(ScenarioEventPubSubType().getName(), "swa::msg::ScenarioEvent");
}

TEST(MsgScenarioEvent, RoundTripPreservesEveryField)
{
    // GIVEN a collision event (non-first enumerator, both ids set, non-empty text)
    ScenarioEvent in;
    in.header(test::make_header(33'000'000'000, 4));
    in.kind(EVENT_COLLISION);
    in.uav_id(5);
    in.other_uav_id(8);
    in.value(0.35);
    in.text("uav 5 hit uav 8 at 0.35 m");

    // WHEN it goes through serialize/deserialize
    const auto out = test::round_trip<ScenarioEventPubSubType>(in);

    // THEN the copy equals the original
    ASSERT_TRUE(out.has_value());
    EXPECT_TRUE(*out == in);
    EXPECT_EQ(out->kind(), EVENT_COLLISION);
    EXPECT_EQ(out->text(), "uav 5 hit uav 8 at 0.35 m");
}

TEST(MsgScenarioEvent, AllUavsSentinelSurvivesRoundTrip)
{
    // GIVEN an event addressed to every UAV, i.e. a negative id
    ScenarioEvent in;
    in.kind(EVENT_SCENARIO_END);
    in.uav_id(ALL_UAVS);
    in.other_uav_id(-1);

    // WHEN it goes through serialize/deserialize
    const auto out = test::round_trip<ScenarioEventPubSubType>(in);

    // THEN the sentinel is still -1 (signed on the wire)
    ASSERT_TRUE(out.has_value());
    EXPECT_EQ(out->uav_id(), -1);
    EXPECT_EQ(out->kind(), EVENT_SCENARIO_END);
}

#include <swa/msg/ClockPubSubTypes.h>

#include "roundtrip.h"

using namespace swa::msg;

TEST(MsgClock, TypeNameIsFullyQualified)
{
    EXPECT_STREQ(ClockPubSubType().getName(), "swa::msg::Clock");
}

TEST(MsgClock, RoundTripPreservesEveryField)
{
    // GIVEN a clock tick whose 64-bit fields exceed 32 bits, to catch narrowing on the wire
    Clock in;
    in.header(test::make_header(9'876'543'210, 5));
    in.step(5'000'000'000ULL);
    in.sim_time_ns(50'000'000'000'000);
    in.step_period_ns(10'000'000);

    // WHEN it goes through serialize/deserialize
    const auto out = test::round_trip<ClockPubSubType>(in);

    // THEN the copy equals the original
    ASSERT_TRUE(out.has_value());
    EXPECT_TRUE(*out == in);
    EXPECT_EQ(out->step(), 5'000'000'000ULL);
    EXPECT_EQ(out->sim_time_ns(), 50'000'000'000'000);
}

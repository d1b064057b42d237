#include <swa/msg/GnssFixPubSubTypes.h>

#include "roundtrip.h"

using namespace swa::msg;

TEST(MsgGnssFix, TypeNameIsFullyQualified)
{
    EXPECT_STREQ(GnssFixPubSubType().getName(), "swa::msg::GnssFix");
}

TEST(MsgGnssFix, RoundTripPreservesEveryField)
{
    // GIVEN a valid fix with every field set to a distinct non-default value
    GnssFix in;
    in.header(test::make_header(5'000'000'001, 9));
    in.uav_id(3);
    in.valid(true);
    in.x_m(-120.5);
    in.y_m(64.25);
    in.std_m(1.75);

    // WHEN it goes through serialize/deserialize
    const auto out = test::round_trip<GnssFixPubSubType>(in);

    // THEN the copy equals the original
    ASSERT_TRUE(out.has_value());
    EXPECT_TRUE(*out == in);
    EXPECT_TRUE(out->valid());
    EXPECT_DOUBLE_EQ(out->x_m(), -120.5);
}

#include <swa/msg/ImuPubSubTypes.h>

#include "roundtrip.h"

using namespace swa::msg;

TEST(MsgImu, TypeNameIsFullyQualified)
{
    EXPECT_STREQ(ImuPubSubType().getName(), "swa::msg::Imu");
}

TEST(MsgImu, RoundTripPreservesEveryField)
{
    // GIVEN an Imu with every field set to a distinct non-default value
    Imu in;
    in.header(test::make_header(1'234'567'890'123, 42));
    in.uav_id(7);
    in.roll_rad(0.125);
    in.pitch_rad(-0.25);
    in.heading_rad(2.5);

    // WHEN it goes through serialize/deserialize
    const auto out = test::round_trip<ImuPubSubType>(in);

    // THEN the copy equals the original
    ASSERT_TRUE(out.has_value());
    EXPECT_TRUE(*out == in);
    EXPECT_EQ(out->header().stamp_ns(), 1'234'567'890'123);
    EXPECT_DOUBLE_EQ(out->heading_rad(), 2.5);
}

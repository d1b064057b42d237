#include <swa/msg/VelocitySetpointPubSubTypes.h>

#include "roundtrip.h"

using namespace swa::msg;

TEST(MsgVelocitySetpoint, TypeNameIsFullyQualified)
{
    EXPECT_STREQ(VelocitySetpointPubSubType().getName(), "swa::msg::VelocitySetpoint");
}

TEST(MsgVelocitySetpoint, RoundTripPreservesEveryField)
{
    // GIVEN a setpoint with every field set to a distinct non-default value
    VelocitySetpoint in;
    in.header(test::make_header(7'000'000'003, 101));
    in.uav_id(11);
    in.vx_mps(-1.5);
    in.vy_mps(2.75);
    in.answered_stamp_ns(6'990'000'000);
    in.answered_seq(100);

    // WHEN it goes through serialize/deserialize
    const auto out = test::round_trip<VelocitySetpointPubSubType>(in);

    // THEN the copy equals the original, including the echoed sensor sample
    ASSERT_TRUE(out.has_value());
    EXPECT_TRUE(*out == in);
    EXPECT_EQ(out->answered_stamp_ns(), 6'990'000'000);
    EXPECT_EQ(out->answered_seq(), 100u);
}

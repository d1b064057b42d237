#include <swa/msg/SwarmTruthPubSubTypes.h>

#include "roundtrip.h"

using namespace swa::msg;

namespace {

UavTruth make_uav(uint32_t id, double base, bool alive, bool gnss_valid)
{
    UavTruth u;
    u.id(id);
    u.x_m(base + 0.5);
    u.y_m(base + 1.5);
    u.vx_mps(base + 2.5);
    u.vy_mps(base + 3.5);
    u.ax_mps2(base + 4.5);
    u.ay_mps2(base + 5.5);
    u.heading_rad(base * 0.01 + 0.125);
    u.alive(alive);
    u.gnss_valid(gnss_valid);
    return u;
}

} // namespace

TEST(MsgSwarmTruth, TypeNamesAreFullyQualified)
{
    EXPECT_STREQ(SwarmTruthPubSubType().getName(), "swa::msg::SwarmTruth");
    EXPECT_STREQ(UavTruthPubSubType().getName(), "swa::msg::UavTruth");
}

TEST(MsgSwarmTruth, RoundTripPreservesEveryField)
{
    // GIVEN a live UAV with GNSS and a dead one without, all kinematics distinct
    SwarmTruth in;
    in.header(test::make_header(1'000'000'000, 100));
    in.uavs().push_back(make_uav(0, 10.0, true, true));
    in.uavs().push_back(make_uav(1, -20.0, false, false));

    // WHEN it goes through serialize/deserialize
    const auto out = test::round_trip<SwarmTruthPubSubType>(in);

    // THEN the copy equals the original
    ASSERT_TRUE(out.has_value());
    EXPECT_TRUE(*out == in);
    ASSERT_EQ(out->uavs().size(), 2u);
    EXPECT_FALSE(out->uavs()[1].alive());
    EXPECT_DOUBLE_EQ(out->uavs()[0].ay_mps2(), 15.5);
}

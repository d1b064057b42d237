#include <swa/msg/DetectionsPubSubTypes.h>

#include "roundtrip.h"

using namespace swa::msg;

namespace {

Detection make_detection(int32_t id, double x_m, double y_m, bool has_cov)
{
    Detection d;
    d.target_id(id);
    d.x_m(x_m);
    d.y_m(y_m);
    d.has_covariance(has_cov);
    d.cov_xx_m2(0.5 + x_m * 0.01);
    d.cov_xy_m2(-0.125);
    d.cov_yy_m2(0.75 + y_m * 0.01);
    return d;
}

} // namespace

TEST(MsgDetections, TypeNamesAreFullyQualified)
{
    EXPECT_STREQ(DetectionsPubSubType().getName(), "swa::msg::Detections");
    EXPECT_STREQ(DetectionPubSubType().getName(), "swa::msg::Detection");
}

TEST(MsgDetections, RoundTripPreservesEveryField)
{
    // GIVEN detections of one identified and one anonymous neighbour
    Detections in;
    in.header(test::make_header(2'500'000'000, 250));
    in.observer_id(4);
    in.detections().push_back(make_detection(9, 10.5, -3.25, true));
    in.detections().push_back(make_detection(ANONYMOUS_ID, -7.75, 1.125, false));

    // WHEN it goes through serialize/deserialize
    const auto out = test::round_trip<DetectionsPubSubType>(in);

    // THEN the copy equals the original, element order included
    ASSERT_TRUE(out.has_value());
    EXPECT_TRUE(*out == in);
    ASSERT_EQ(out->detections().size(), 2u);
    EXPECT_EQ(out->detections()[1].target_id(), -1);
    EXPECT_DOUBLE_EQ(out->detections()[0].cov_xy_m2(), -0.125);
}

TEST(MsgDetections, OversizeListStillReachesTheConsumer)
{
    // GIVEN more detections than the consumer's bound (64) and than the 100 elements fastddsgen
    // assumes for unbounded sequences when computing the type's max size
    Detections in;
    in.observer_id(1);
    for (int32_t i = 0; i < 150; ++i) {
        in.detections().push_back(make_detection(i, i * 0.5, -i * 0.25, (i % 2) == 0));
    }

    // WHEN it goes through serialize/deserialize
    const auto out = test::round_trip<DetectionsPubSubType>(in);

    // THEN nothing is truncated: rejecting oversize input is the consumer's job, not the transport's
    ASSERT_TRUE(out.has_value());
    EXPECT_EQ(out->detections().size(), 150u);
    EXPECT_TRUE(*out == in);
}

// The simulator's PX4 stand-in (swa/sim/px4_standin.h): PX4's offboard rules as the bridge meets them, on simulation
// time (10 ms steps).

#include <gtest/gtest.h>

#include <string>

#include "swa/px4/vehicle.h"
#include "swa/sim/px4_standin.h"

namespace swa::sim {
namespace {

constexpr agent::StampNs kStepNs = 10'000'000;
constexpr std::uint8_t kAccepted = 0, kTemporarilyRejected = 1, kUnsupported = 3;

class Px4StandinTest : public ::testing::Test {
 protected:
  // The bridge's stream for steps [from, to): a heartbeat and a velocity setpoint (east 1 m/s) each step, the
  // vehicle's decision after each.
  Px4Standin::Decision stream(int from, int to, bool velocity_only = true) {
    Px4Standin::Decision d;
    for (int k = from; k < to; ++k) {
      px4.offboardControlMode(k * kStepNs, true);
      px4.trajectorySetpoint({0.0, 1.0, 0.0}, velocity_only);
      d = px4.step(k * kStepNs);
    }
    return d;
  }
  std::uint8_t requestOffboard(int k) {
    return px4.vehicleCommand(k * kStepNs, px4::kCmdDoSetMode, px4::kModeFlagCustomModeEnabled,
                              px4::kCustomMainModeOffboard);
  }

  Px4Standin px4{1.0};  // COM_OF_LOSS_T = 1 s
};

TEST_F(Px4StandinTest, HoldsUntilOffboardIsRequestedWithTheStreamRunning) {
  // GIVEN the vehicle as the scenario starts: armed, in Hold
  EXPECT_EQ(px4.armingState(), px4::kArmingStateArmed);
  EXPECT_EQ(px4.navState(), px4::kNavStateAutoLoiter);
  // WHEN offboard is requested before any offboard_control_mode THEN PX4 refuses it
  EXPECT_EQ(requestOffboard(0), kTemporarilyRejected);
  // WHEN the bridge streams without asking THEN the vehicle still holds
  EXPECT_FALSE(stream(0, 100).following);
  // WHEN offboard is requested with the stream running THEN it is accepted and the vehicle flies the setpoint
  EXPECT_EQ(requestOffboard(100), kAccepted);
  const Px4Standin::Decision d = stream(100, 101);
  EXPECT_TRUE(d.following);
  EXPECT_EQ(d.velocity_mps, agent::Vec2(1.0, 0.0));  // NED east = stable x
  EXPECT_EQ(px4.navState(), px4::kNavStateOffboard);
}

TEST_F(Px4StandinTest, LosingTheHeartbeatForComOfLossTIsTheFailsafe) {
  // GIVEN the vehicle in OFFBOARD on the stream
  stream(0, 10);
  ASSERT_EQ(requestOffboard(10), kAccepted);
  stream(10, 50);
  px4.takeEvents();
  // WHEN the stream stops after step 49
  int lost_at = -1;
  for (int k = 50; k < 300; ++k) {
    const Px4Standin::Decision d = px4.step(k * kStepNs);
    if (!d.following && lost_at < 0) lost_at = k;
    if (lost_at >= 0) {
      EXPECT_EQ(d.velocity_mps, agent::Vec2::Zero());
    }
  }
  // THEN the vehicle keeps the last setpoint for COM_OF_LOSS_T, then holds in failsafe and says so
  EXPECT_EQ(lost_at, 49 + 101);
  EXPECT_TRUE(px4.failsafe());
  EXPECT_EQ(px4.navState(), px4::kNavStateAutoLoiter);
  const auto events = px4.takeEvents();
  ASSERT_EQ(events.size(), 1u);
  EXPECT_NE(events[0].text.find("offboard lost"), std::string::npos) << events[0].text;
  EXPECT_EQ(events[0].control, StandinEvent::Control::kLost);
  EXPECT_NEAR(px4.lostAfterS(), 1.01, 1e-9);
  // AND it does not return to OFFBOARD by itself when the stream comes back, only when asked again
  EXPECT_FALSE(stream(300, 400).following);
  EXPECT_EQ(requestOffboard(400), kAccepted);
  EXPECT_TRUE(stream(400, 401).following);
  EXPECT_FALSE(px4.failsafe());
}

TEST_F(Px4StandinTest, SetpointsItDoesNotSimulateHoldTheVehicleAndAreReportedOnce) {
  stream(0, 10);
  ASSERT_EQ(requestOffboard(10), kAccepted);
  px4.takeEvents();
  // WHEN a setpoint carries a position THEN the vehicle holds, and it is reported once
  EXPECT_FALSE(stream(10, 20, /*velocity_only=*/false).following);
  EXPECT_EQ(px4.takeEvents().size(), 1u);
  // AND the velocity-only stream is flown again at once
  EXPECT_TRUE(stream(20, 21).following);
  // AND commands other than arm / offboard are unsupported, arming is accepted
  EXPECT_EQ(px4.vehicleCommand(0, 21, 0.0f, 0.0f), kUnsupported);
  EXPECT_EQ(px4.vehicleCommand(0, px4::kCmdComponentArmDisarm, 1.0f, 0.0f), kAccepted);
}

}  // namespace
}  // namespace swa::sim

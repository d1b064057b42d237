// The stand-ins' estimators (issue #43): PX4's EKF2 and ArduPilot's EKF3 as far as they decide whether the vehicle
// stays under SWA's control after GNSS is lost (swa/sim/px4_estimator.h, ardupilot_estimator.h), and the stand-ins'
// rules on top of them (px4_standin.h, ardupilot_standin.h). The times are the autopilots' own: EKF2_NOAID_TOUT after
// the last GNSS fix (4.4 s after the last external vision sample), EKF3's 7 s without a position and the EKF
// failsafe's 1 s.

#include <gtest/gtest.h>

#include <optional>

#include "swa/autopilot/ardupilot.h"
#include "swa/px4/vehicle.h"
#include "swa/sim/ardupilot_estimator.h"
#include "swa/sim/ardupilot_standin.h"
#include "swa/sim/px4_estimator.h"
#include "swa/sim/px4_standin.h"

namespace swa::sim {
namespace {

constexpr agent::StampNs kMs = 1'000'000;
constexpr agent::StampNs kStep = 10 * kMs;  // the simulator's 100 Hz

// The first step at which `valid` turns false, from `from` on, stepping at 100 Hz up to `until`.
template <class Valid, class Step>
std::optional<agent::StampNs> firstInvalid(agent::StampNs from, agent::StampNs until, Step step, Valid valid) {
  for (agent::StampNs t = from; t <= until; t += kStep) {
    step(t);
    if (!valid()) return t;
  }
  return std::nullopt;
}

TEST(Px4Estimator, WithoutGnssOrVisionTheLocalPositionTurnsInvalidAfterNoaidTout) {
  // GIVEN EKF2 with its defaults, GNSS fused at 10 Hz until 10 s
  Px4Estimator ekf(Px4EstimatorParams{});
  for (agent::StampNs t = 0; t <= 10'000 * kMs; t += kStep) {
    ekf.gnss(t, t % (100 * kMs) == 0);
    ekf.update(t);
  }
  ASSERT_TRUE(ekf.xyValid());
  EXPECT_FALSE(ekf.deadReckoning());
  // WHEN GNSS is gone THEN it dead-reckons after 1 s and the position turns invalid EKF2_NOAID_TOUT (5 s) after the
  // last fix
  const auto invalid = firstInvalid(
      10'010 * kMs, 20'000 * kMs, [&](agent::StampNs t) { ekf.update(t); }, [&] { return ekf.xyValid(); });
  ASSERT_TRUE(invalid);
  EXPECT_EQ(*invalid, 15'010 * kMs);
  EXPECT_TRUE(ekf.deadReckoning());
  // AND a fix makes it valid again at once
  ekf.gnss(*invalid + kStep, true);
  ekf.update(*invalid + kStep);
  EXPECT_TRUE(ekf.xyValid());
}

TEST(Px4Estimator, ExternalVisionKeepsItValidAndItsEndStartsTheTimeout) {
  // GIVEN GNSS until 10 s, then external vision (position and velocity) at 10 Hz until 30 s
  Px4Estimator ekf(Px4EstimatorParams{});
  for (agent::StampNs t = 0; t <= 30'000 * kMs; t += kStep) {
    ekf.gnss(t, t <= 10'000 * kMs);
    if (t > 10'000 * kMs && t % (100 * kMs) == 0) ekf.externalVision(t, true, true);
    ekf.update(t);
    // THEN it stays valid and aided throughout
    ASSERT_TRUE(ekf.xyValid()) << t;
    if (t > 10'200 * kMs) {
      ASSERT_TRUE(ekf.visionInUse()) << t;
    }
  }
  // WHEN the vision stops THEN EKF2 stops using it after 0.4 s, and the position is invalid 4.4 s after the last sample
  const auto invalid = firstInvalid(
      30'010 * kMs, 40'000 * kMs, [&](agent::StampNs t) { ekf.update(t); }, [&] { return ekf.xyValid(); });
  ASSERT_TRUE(invalid);
  EXPECT_EQ(*invalid, 34'410 * kMs);
}

TEST(Px4Estimator, VisionCountsOnlyForWhatEv_ctrlFusesAndOnlyAtMoreThan5Hz) {
  // GIVEN PX4 v1.16's default EKF2_EV_CTRL = 0: nothing is fused
  Px4Estimator off(Px4EstimatorParams{5.0, 0});
  EXPECT_FALSE(off.visionFusable(true, true));
  // AND with velocity only (bit 2), a position-only sample is not
  Px4Estimator velocity(Px4EstimatorParams{5.0, 4});
  EXPECT_TRUE(velocity.visionFusable(false, true));
  EXPECT_FALSE(velocity.visionFusable(true, false));
  // WHEN samples come at 4 Hz (250 ms apart, above EV_MAX_INTERVAL) THEN vision never starts
  Px4Estimator slow(Px4EstimatorParams{});
  for (agent::StampNs t = 0; t <= 2'000 * kMs; t += 250 * kMs) {
    slow.externalVision(t, true, true);
    slow.update(t);
  }
  EXPECT_FALSE(slow.visionInUse());
  EXPECT_FALSE(slow.xyValid());  // never aided: EKF2's flag starts invalid
}

TEST(ArdupilotEstimator, WithoutGpsOrExternalNavThePositionIsLostAfter7sAndTheFailsafeFollowsAfter1s) {
  ArdupilotEstimator ekf(ArdupilotEstimatorParams{});
  for (agent::StampNs t = 0; t <= 10'000 * kMs; t += kStep) {
    ekf.gps(t, t % (100 * kMs) == 0 || t < 10'000 * kMs);
    ekf.update(t);
  }
  ASSERT_TRUE(ekf.positionOk());
  const auto lost = firstInvalid(
      10'010 * kMs, 30'000 * kMs,
      [&](agent::StampNs t) {
        ekf.gps(t, false);
        ekf.update(t);
      },
      [&] { return ekf.positionOk(); });
  ASSERT_TRUE(lost);
  EXPECT_EQ(*lost, 17'010 * kMs);
  EXPECT_FALSE(ekf.ekfFailsafe());
  const auto failsafe = firstInvalid(
      *lost, 30'000 * kMs, [&](agent::StampNs t) { ekf.update(t); }, [&] { return !ekf.ekfFailsafe(); });
  ASSERT_TRUE(failsafe);
  EXPECT_EQ(*failsafe, 18'010 * kMs);
}

TEST(ArdupilotEstimator, ExternalOdometryStampedOnTheVehiclesClockKeepsThePositionOnlyWhenGpsIsGone) {
  ArdupilotEstimator ekf(ArdupilotEstimatorParams{});
  // GIVEN GPS good: the odometry is not the active source
  ekf.gps(0, true);
  EXPECT_FALSE(ekf.externalOdometry(0, 0));
  // WHEN GPS is gone and odometry comes at 10 Hz stamped 0 (as the bridge stamps it) THEN it is fused, for 30 s
  for (agent::StampNs t = kStep; t <= 30'000 * kMs; t += kStep) {
    ekf.gps(t, false);
    if (t % (100 * kMs) == 0) {
      EXPECT_TRUE(ekf.externalOdometry(t, 0));
    }
    ekf.update(t);
    ASSERT_TRUE(ekf.positionOk()) << t;
  }
  EXPECT_TRUE(ekf.externalNavInUse());
  // AND a stamp after the vehicle's time (a UTC stamp) is never fused
  EXPECT_FALSE(ekf.externalOdometry(30'000 * kMs, 1'700'000'000'000'000'000));
  // AND with ArduPilot's own defaults (no external navigation) it is not either
  ArdupilotEstimator defaults(ArdupilotEstimatorParams{false});
  defaults.gps(0, false);
  EXPECT_FALSE(defaults.externalOdometry(kStep, 0));
}

TEST(Px4StandinWithEkf, OffboardIsRefusedWithoutAValidVelocityAndLostWhenItTurnsInvalid) {
  Px4Standin px4(1.0, Px4EstimatorParams{});
  agent::StampNs t = 0;
  const auto stream = [&](agent::StampNs until, bool gnss) {
    std::optional<Px4Standin::Decision> d;
    for (; t <= until; t += kStep) {
      px4.gnss(t, gnss);
      px4.offboardControlMode(t, true);
      px4.trajectorySetpoint(px4::NedVelocity{1.0, 0.0, 0.0}, true);
      d = px4.step(t);
    }
    return *d;
  };
  // GIVEN no GNSS from the start: DO_SET_MODE to offboard is temporarily rejected
  stream(500 * kMs, false);
  EXPECT_EQ(px4.vehicleCommand(t, px4::kCmdDoSetMode, px4::kModeFlagCustomModeEnabled, px4::kCustomMainModeOffboard),
            1);
  // WHEN GNSS comes THEN offboard is accepted and the vehicle follows
  stream(1'000 * kMs, true);
  ASSERT_EQ(px4.vehicleCommand(t, px4::kCmdDoSetMode, px4::kModeFlagCustomModeEnabled, px4::kCustomMainModeOffboard),
            0);
  EXPECT_TRUE(stream(2'000 * kMs, true).following);
  px4.takeEvents();
  // WHEN GNSS is lost THEN it follows for EKF2_NOAID_TOUT, then falls back to Altitude mode, out of SWA's control
  EXPECT_TRUE(stream(6'900 * kMs, false).following);
  EXPECT_FALSE(stream(7'100 * kMs, false).following);
  EXPECT_EQ(px4.navState(), px4::kNavStateAltctl);
  EXPECT_TRUE(px4.failsafe());
  const std::vector<StandinEvent> events = px4.takeEvents();
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].control, StandinEvent::Control::kLost);
  EXPECT_NE(events[0].text.find("EKF2_NOAID_TOUT"), std::string::npos) << events[0].text;
}

TEST(Px4StandinWithEkf, ExternalVisionKeepsTheVehicleInOffboardWithoutGnss) {
  Px4Standin px4(1.0, Px4EstimatorParams{});
  agent::StampNs t = 0;
  for (; t <= 60'000 * kMs; t += kStep) {
    const bool gnss = t < 2'000 * kMs;
    px4.gnss(t, gnss);
    if (!gnss && t % (100 * kMs) == 0) px4.visualOdometry(t, true, true);
    px4.offboardControlMode(t, true);
    px4.trajectorySetpoint(px4::NedVelocity{1.0, 0.0, 0.0}, true);
    if (t == 1'000 * kMs) {
      ASSERT_EQ(
          px4.vehicleCommand(t, px4::kCmdDoSetMode, px4::kModeFlagCustomModeEnabled, px4::kCustomMainModeOffboard), 0);
    }
    const Px4Standin::Decision d = px4.step(t);
    if (t > 1'000 * kMs) {
      ASSERT_TRUE(d.following) << t;
    }
  }
  EXPECT_TRUE(px4.localPositionValid());
  EXPECT_FALSE(px4.deadReckoning());
}

TEST(Px4StandinWithEkf, WhenTheVisionStopsTheOffboardLossHoldDescendsOnceThePositionIsGone) {
  Px4Standin px4(1.0, Px4EstimatorParams{});
  agent::StampNs t = 0;
  const auto fly = [&](agent::StampNs until, bool gnss, bool vision, bool offboard) {
    for (; t <= until; t += kStep) {
      px4.gnss(t, gnss);
      if (vision && t % (100 * kMs) == 0) px4.visualOdometry(t, true, true);
      if (offboard) {
        px4.offboardControlMode(t, true);
        px4.trajectorySetpoint(px4::NedVelocity{1.0, 0.0, 0.0}, true);
      }
      px4.step(t);
    }
  };
  // GIVEN a vehicle in offboard on external vision after GNSS was lost at 2 s
  fly(1'000 * kMs, true, false, true);
  ASSERT_EQ(px4.vehicleCommand(t, px4::kCmdDoSetMode, px4::kModeFlagCustomModeEnabled, px4::kCustomMainModeOffboard),
            0);
  fly(2'000 * kMs, true, false, true);
  fly(10'000 * kMs, false, true, true);
  px4.takeEvents();
  // WHEN everything stops at 10 s (the agent killed: no command, no odometry)
  // THEN COM_OF_LOSS_T later the offboard-loss failsafe holds ...
  fly(11'200 * kMs, false, false, false);
  EXPECT_EQ(px4.navState(), px4::kNavStateAutoLoiter);
  EXPECT_TRUE(px4.localPositionValid());
  // ... and once EKF2 has dead-reckoned EKF2_NOAID_TOUT past its last aiding, Hold cannot run: Descend
  fly(14'300 * kMs, false, false, false);
  EXPECT_EQ(px4.navState(), px4::kNavStateAutoLoiter);
  fly(14'600 * kMs, false, false, false);
  EXPECT_FALSE(px4.localPositionValid());
  EXPECT_EQ(px4.navState(), px4::kNavStateDescend);
  EXPECT_TRUE(px4.failsafe());
  const std::vector<StandinEvent> events = px4.takeEvents();
  ASSERT_EQ(events.size(), 2u);
  EXPECT_NE(events[0].text.find("COM_OF_LOSS_T"), std::string::npos) << events[0].text;
  EXPECT_EQ(events[1].control, StandinEvent::Control::kLost);
  EXPECT_NE(events[1].text.find("Descend"), std::string::npos) << events[1].text;
  // AND once descending, it stays so: one event
  fly(20'000 * kMs, false, false, false);
  EXPECT_TRUE(px4.takeEvents().empty());
}

TEST(ArdupilotStandinWithEkf, GuidedNeedsAPositionAndTheEkfFailsafeLandsTheVehicle) {
  ArdupilotStandin ap(3.0, ArdupilotEstimatorParams{false});  // ArduPilot's defaults: no external navigation
  agent::StampNs t = 0;
  const auto run = [&](agent::StampNs until, bool gps) {
    ArdupilotStandin::Decision d;
    for (; t <= until; t += kStep) {
      ap.gnss(t, gps);
      ap.cmdVel(t, true, ardupilot::EnuTwist{1.0, 0.0, 0.0, 0.0});
      d = ap.step(t);
    }
    return d;
  };
  run(500 * kMs, true);
  ASSERT_TRUE(ap.modeSwitch(ardupilot::kModeGuided).status);
  EXPECT_TRUE(run(1'000 * kMs, true).following);
  ap.takeEvents();
  // WHEN GPS is lost THEN it follows for 7 s, then 1 s later the EKF failsafe lands it
  EXPECT_TRUE(run(7'900 * kMs, false).following);
  EXPECT_FALSE(run(9'100 * kMs, false).following);
  EXPECT_EQ(ap.mode(), ardupilot::kModeLand);
  const std::vector<StandinEvent> events = ap.takeEvents();
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].control, StandinEvent::Control::kLost);
  // AND GUIDED is refused while it has no position
  EXPECT_FALSE(ap.modeSwitch(ardupilot::kModeGuided).status);
  EXPECT_EQ(ap.mode(), ardupilot::kModeLand);
}

TEST(StandinsWithoutEkf, KeepTheirEstimateValidAsBeforeIssue43) {
  Px4Standin px4(1.0);
  px4.gnss(0, false);
  px4.step(100 * kMs);
  EXPECT_TRUE(px4.localPositionValid());
  EXPECT_FALSE(px4.modelsEstimator());
  ArdupilotStandin ap(3.0);
  ap.gnss(0, false);
  ap.step(20'000 * kMs);
  EXPECT_TRUE(ap.positionOk());
  EXPECT_FALSE(ap.ekfFailsafe());
}

}  // namespace
}  // namespace swa::sim

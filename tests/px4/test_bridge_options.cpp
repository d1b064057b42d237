// swa_px4_bridge's command line (bridge_options.h): every option read, every problem reported together.

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <vector>

#include "bridge_options.h"
#include "error_text.h"

namespace swa::bridge_node {
namespace {

std::string problemsOf(const std::vector<std::string>& args) {
  return testing::invalidArgumentText([&] { parseBridgeOptions(args); });
}

TEST(BridgeOptions, ParsesEveryOption) {
  const BridgeOptions o = parseBridgeOptions({"--id",
                                              "3",
                                              "--px4-namespace",
                                              "/lab/vehicle_3",
                                              "--target-system",
                                              "4",
                                              "--stale-after-s",
                                              "0.2",
                                              "--agent-lost-after-s",
                                              "2",
                                              "--attitude-lost-after-s",
                                              "0.4",
                                              "--heartbeat-period-s",
                                              "0.02",
                                              "--max-speed-mps",
                                              "3",
                                              "--max-yaw-rate-radps",
                                              "0.75",
                                              "--engage",
                                              "--domain",
                                              "7",
                                              "--summary-out",
                                              "/tmp/b.json",
                                              "--px4-release",
                                              "1.16.1"});
  EXPECT_EQ(o.id, 3);
  EXPECT_EQ(o.px4_release, px4::Release::kV1_16);
  EXPECT_EQ(px4Namespace(o), "lab/vehicle_3");
  EXPECT_EQ(o.target_system, 4);
  EXPECT_DOUBLE_EQ(o.core.stale_after_s, 0.2);
  EXPECT_DOUBLE_EQ(o.core.agent_lost_after_s, 2.0);
  EXPECT_DOUBLE_EQ(o.core.attitude_lost_after_s, 0.4);
  EXPECT_DOUBLE_EQ(o.core.heartbeat_period_s, 0.02);
  EXPECT_DOUBLE_EQ(o.core.max_speed_mps, 3.0);
  EXPECT_DOUBLE_EQ(o.core.max_yaw_rate_radps, 0.75);
  EXPECT_TRUE(o.core.engage);
  EXPECT_EQ(o.domain, std::optional<std::string>("7"));
  EXPECT_EQ(o.summary_out, "/tmp/b.json");
}

TEST(BridgeOptions, DefaultsAreSafeAndTheNamespaceIsTheSimulators) {
  const BridgeOptions o = parseBridgeOptions({"--id", "2"});
  // Never engages unless told; PX4's namespace px4_<I>, as swa_sim's stand-in; "" means none.
  EXPECT_FALSE(o.core.engage);
  EXPECT_EQ(px4Namespace(o), "px4_2");
  EXPECT_EQ(px4Namespace(parseBridgeOptions({"--id", "2", "--px4-namespace", ""})), "");
  EXPECT_LE(o.core.heartbeat_period_s, 0.1);  // at least 10 Hz
  EXPECT_LT(o.core.stale_after_s, o.core.agent_lost_after_s);
  // The newest PX4 release unless told
  EXPECT_EQ(o.px4_release, px4::Release::kV1_17);
}

TEST(BridgeOptions, EveryProblemIsReportedTogether) {
  const std::string p = problemsOf({"--px4-namespace", "px4-1", "--heartbeat-period-s", "0.5", "--stale-after-s", "2",
                                    "--agent-lost-after-s", "1", "--bogus", "--px4-release", "1.14"});
  EXPECT_NE(p.find("--id"), std::string::npos) << p;
  EXPECT_NE(p.find("--px4-namespace 'px4-1'"), std::string::npos) << p;
  EXPECT_NE(p.find("--heartbeat-period-s"), std::string::npos) << p;
  EXPECT_NE(p.find("--stale-after-s must be below --agent-lost-after-s"), std::string::npos) << p;
  EXPECT_NE(p.find("--bogus"), std::string::npos) << p;
  EXPECT_NE(p.find("--px4-release '1.14': not a supported PX4 release (v1.15, v1.16, v1.17)"), std::string::npos) << p;
  EXPECT_TRUE(parseBridgeOptions({"--help"}).help);
}

TEST(BridgeOptions, ArdupilotHasItsOwnNamespaceAndQuaternionLayoutAndNoneOfPx4s) {
  // GIVEN --autopilot ardupilot THEN its namespace defaults to AP_DDS's ap/v<I+1> and the core speaks ArduPilot
  const BridgeOptions o = parseBridgeOptions({"--id", "2", "--autopilot", "ardupilot", "--no-gnss"});
  EXPECT_EQ(o.autopilot, AutopilotKind::kArdupilot);
  EXPECT_EQ(apNamespace(o), "ap/v3");
  EXPECT_FALSE(o.ap_quaternion.has_value());  // auto: decided from gravity
  EXPECT_STREQ(o.core.autopilot.name, "ArduPilot");
  EXPECT_EQ(o.core.autopilot.control_mode, ardupilot::kModeGuided);
  const BridgeOptions single = parseBridgeOptions(
      {"--id", "0", "--autopilot", "ardupilot", "--no-gnss", "--ap-namespace", "/ap", "--ap-quaternion", "wxyz"});
  EXPECT_EQ(apNamespace(single), "ap");
  EXPECT_EQ(single.ap_quaternion, ardupilot::QuaternionLayout::kWxyzInXyzw);
  EXPECT_EQ(parseBridgeOptions({"--id", "0", "--autopilot", "ardupilot", "--ap-quaternion", "ros"}).ap_quaternion,
            ardupilot::QuaternionLayout::kRos);
  // AND PX4's options and an unknown autopilot are refused
  const std::string p = problemsOf({"--id", "0", "--autopilot", "ardupilot", "--px4-release", "1.16"});
  EXPECT_NE(p.find("are PX4's: not with --autopilot ardupilot"), std::string::npos) << p;
  EXPECT_FALSE(parseBridgeOptions({"--id", "0", "--autopilot", "ardupilot"}).no_gnss);  // GNSS forwarded by default
  // AND how long navsat may be silent is set for firmware that sends it at 1 Hz; a bad value or PX4 is refused
  EXPECT_EQ(parseBridgeOptions({"--id", "0", "--autopilot", "ardupilot"}).navsat.silence_s, 0.5);
  EXPECT_EQ(parseBridgeOptions({"--id", "0", "--autopilot", "ardupilot", "--gnss-silence-s", "1.5"}).navsat.silence_s,
            1.5);
  EXPECT_NE(problemsOf({"--id", "0", "--autopilot", "ardupilot", "--gnss-silence-s", "nan"})
                .find("--gnss-silence-s 'nan': a time in seconds in [0.05, 10]"),
            std::string::npos);
  EXPECT_NE(problemsOf({"--id", "0", "--gnss-silence-s", "1"}).find("are ArduPilot's: add --autopilot ardupilot"),
            std::string::npos);
  EXPECT_NE(problemsOf({"--id", "0", "--autopilot", "apm"}).find("--autopilot 'apm': px4 or ardupilot"),
            std::string::npos);
  EXPECT_NE(problemsOf({"--id", "0", "--ap-namespace", "ap"}).find("add --autopilot ardupilot"), std::string::npos);
  EXPECT_NE(problemsOf({"--id", "0", "--autopilot", "ardupilot", "--no-gnss", "--ap-quaternion", "xyz"})
                .find("--ap-quaternion 'xyz': auto, ros or wxyz"),
            std::string::npos);
  // AND the default stays PX4
  EXPECT_STREQ(parseBridgeOptions({"--id", "0"}).core.autopilot.name, "PX4");
}

}  // namespace
}  // namespace swa::bridge_node

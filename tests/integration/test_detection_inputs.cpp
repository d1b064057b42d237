// Detections as real detectors publish them (issue #27), end to end with swa_launch: the simulator publishes each
// UAV's detections as a vision_msgs/Detection3DArray or as UVDAR's mrs_msgs/PoseWithCovarianceArrayStamped
// (agent.sensor.input), and the agents read them through their adapter. 8 UAVs, lockstep: as cohesive as with SWA's own
// Detections, whose lockstep runs equal the in-process loop (test_dds_swarm.cpp).

#include <signal.h>

#include <iostream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "closed_loop.h"
#include "launch_support.h"
#include "process_test.h"
#include "swa/sim/scenario_io.h"

namespace swa::testing {
namespace {

const std::string kScenarioDir = std::string(SWA_SOURCE_DIR) + "/deploy/scenarios/";
constexpr double kRunBoundS = 180.0;
// As through PX4: d_NB within 0.5 % of r (10 m). Measured: equal to the last digit (the adapters lose nothing the
// simulator's detections carry).
constexpr double kDnbToleranceM = 0.05;

class DetectionInputs : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = freshTestDir("swa_detection_inputs", /*per_test=*/true);
    useOwnSwarm();
  }
  void TearDown() override {
    for (int pid : processesOnDomain(domain_)) ::kill(pid, SIGKILL);  // only after a failed check
    janitor_.clean();
    if (!HasFailure()) fs::remove_all(dir_);
  }

  void expectAsCohesiveAsNative(const std::string& scenario, const std::string& input) {
    SCOPED_TRACE(scenario + " through " + input);
    const std::vector<std::string> sets = {"duration_s=60"};
    const double d_native =
        batch::runClosedLoop(sim::loadScenario(kScenarioDir + scenario, sets)).summary.mean_neighbor_distance_m;
    const fs::path out = dir_ / (scenario + "_" + input);
    Child child({SWA_LAUNCH_BINARY, "--scenario", kScenarioDir + scenario, "--domain", std::to_string(domain_), "--out",
                 out.string(), "--set", "duration_s=60", "--set", "agent.sensor.input=" + input},
                dir_ / (scenario + "_" + input + ".log"));
    const std::optional<int> status = child.wait(kRunBoundS);
    ASSERT_TRUE(status) << "still running after " << kRunBoundS << " s";
    const std::string summary = readFile(out / "summary.json");
    EXPECT_EQ(*status, 0) << summary << readFile(out / "logs" / "agent_0.log");
    const double d = jsonNumber(summary, "mean_neighbor_distance_m");
    std::cout << scenario << ": d_NB native (in-process) " << d_native << " m, through " << input << " " << d << " m\n";
    EXPECT_NEAR(d, d_native, kDnbToleranceM);
    EXPECT_EQ(jsonNumber(summary, "collisions"), 0.0);
    EXPECT_EQ(jsonNumber(summary, "groups"), 1.0);
    // AND the agents read every set through the adapter, none dropped
    const std::string log = readFile(out / "logs" / "agent_0.log");
    EXPECT_NE(log.find(input + " detections:"), std::string::npos) << log;
    EXPECT_NE(log.find("dropped 0 in a frame it cannot place, 0 with a bad stamp, 0 oversize, 0 detection(s)"),
              std::string::npos)
        << log;
  }

  OwnShm own_shm_;  // first: this test's /dev/shm is its own (private_shm.h)
  ShmJanitor janitor_;
  fs::path dir_;
  int domain_ = testDomain(43);
};

TEST_F(DetectionInputs, EightUavsReadingVisionMsgsOrUvdarAreAsCohesiveAsWithSwasOwnDetections) {
  expectAsCohesiveAsNative("dropout_8.yaml", "vision_msgs");
  expectAsCohesiveAsNative("dropout_8.yaml", "uvdar");
  // An anonymous sensor (no ids: a LiDAR clusterer) through vision_msgs
  expectAsCohesiveAsNative("anonymous_8.yaml", "vision_msgs");
}

}  // namespace
}  // namespace swa::testing

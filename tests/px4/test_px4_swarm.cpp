// The swarm through an autopilot (issues #13, #27), end to end with swa_launch: the simulator plays each UAV's PX4
// autopilot of a release (vehicle.interface = px4, vehicle.px4_release) or its ArduPilot Copter (vehicle.interface =
// ardupilot), one swa_px4_bridge per agent; a PX4 that moves its local origin mid-flight (issue #46). Checked from the
// outside: the run's summary.json, events.csv, trajectories.csv, restarts.csv, the recording and the endpoints DDS
// discovery reports.

#include <signal.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <swa/msg/GnssFixPubSubTypes.h>
#include <swa/msg/VelocitySetpointPubSubTypes.h>

#include "../integration/discovery_observer.h"
#include "../integration/launch_support.h"
#include "../integration/own_ports.h"
#include "../integration/private_shm.h"
#include "../integration/process_test.h"
#include "closed_loop.h"
#include "recorded_run.h"
#include "replay_check.h"
#include "swa/dds/topics.h"
#include "swa/px4/release.h"
#include "swa/sim/scenario_io.h"

namespace swa::testing {
namespace {

const std::string kScenarioDir = std::string(SWA_SOURCE_DIR) + "/deploy/scenarios/";

// The in-process closed loop's mean neighbour distance for a shipped scenario with `sets`: what a launched run
// through an autopilot is held to.
double inProcessDnb(const std::string& scenario, const std::vector<std::string>& sets) {
  return batch::runClosedLoop(sim::loadScenario(kScenarioDir + scenario, sets)).summary.mean_neighbor_distance_m;
}

constexpr double kRunBoundS = 240.0;
// A run through PX4 may differ from the direct one only by the float32 of PX4's messages and the second of Hold
// before the bridges engage offboard: d_NB within 0.5 % of r (10 m). Measured: 0.002 m (4 UAVs), 0.005 m (8 UAVs).
constexpr double kDnbToleranceM = 0.05;

struct LaunchedRun {
  int status = -1;
  std::string summary;
  fs::path dir;
};

class Px4SwarmTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = freshTestDir("swa_px4_swarm", /*per_test=*/true);
    useOwnSwarm();  // the launcher and this test's observers in a DDS partition of their own
  }
  void TearDown() override {
    for (int pid : processesOnDomain(domain_)) ::kill(pid, SIGKILL);  // only after a failed check
    janitor_.clean();
    if (!HasFailure()) fs::remove_all(dir_);
  }

  // After the launcher exited: no process of the run and no shared-memory file of ours left. `since` (default: the
  // fixture's janitor) names what existed before: a killed bridge may have kept port files of the test's own
  // participants referenced, which are the test's to clean, not the launcher's.
  void expectNothingLeft(const ShmJanitor* since = nullptr) const {
    EXPECT_TRUE(processesOnDomain(domain_).empty()) << "processes left on domain " << domain_;
    std::string left;
    for (const std::string& f : ofDomain((since ? *since : janitor_).zombies(), domain_)) left += " " + f;
    EXPECT_TRUE(left.empty()) << "shared-memory files left behind:" << left;
  }

  std::vector<std::string> launchArgs(const std::string& scenario, const std::string& vehicle, const fs::path& out,
                                      const std::vector<std::string>& sets = {}, bool record = false) const {
    std::vector<std::string> argv{SWA_LAUNCH_BINARY, "--scenario", kScenarioDir + scenario, "--vehicle",
                                  vehicle,           "--domain",   std::to_string(domain_), "--out",
                                  out.string()};
    for (const std::string& s : sets) argv.insert(argv.end(), {"--set", s});
    if (record) argv.emplace_back("--record");
    return argv;
  }

  // `tag` tells apart runs of one scenario and vehicle (their directories and logs); `record`: into run.mcap.
  LaunchedRun launch(const std::string& scenario, const std::string& vehicle, const std::vector<std::string>& sets = {},
                     const std::string& tag = "", bool record = false) {
    LaunchedRun r;
    const std::string name = scenario + "_" + vehicle + (tag.empty() ? "" : "_" + tag);
    r.dir = dir_ / name;
    Child child(launchArgs(scenario, vehicle, r.dir, sets, record), dir_ / (name + ".log"));
    r.status = child.wait(kRunBoundS).value_or(-1);
    r.summary = readFile(r.dir / "summary.json");
    return r;
  }

  void expectAsCohesiveAsDirect(const std::string& scenario, const std::vector<px4::Release>& releases);
  // Through ArduPilot; with `observer`, the bridges' endpoints are audited too.
  void expectThroughArdupilotAsCohesiveAsDirect(const std::string& scenario, DiscoveryObserver* observer);
  void expectGnssLostAndRegainedThroughTheBridges(const std::string& vehicle, const std::string& name);

  // Runs swa_launch with `args` (its log: dir_/`log`) and SIGKILLs UAV `victim`'s bridge once that UAV's agent has
  // published its state for `kill_at_ns`; `status` gets the launcher's exit status. Afterwards no process of the run
  // left shared memory behind.
  void runKillingTheBridge(const std::vector<std::string>& args, const std::string& log, int victim,
                           std::int64_t kill_at_ns, std::optional<int>& status) {
    auto watch = std::make_unique<StateStampWatch>(domain_, victim);
    const ShmJanitor since_watch;
    Child launch(args, dir_ / log);
    ASSERT_GT(
        watch->killWhenReached(kill_at_ns, launch, [&] { return uavProcessPid(domain_, "swa_px4_bridge", victim); }), 0)
        << readFile(dir_ / log);
    status = launch.wait(kRunBoundS);
    watch.reset();
    ASSERT_TRUE(status) << "swa_launch still running";
    expectNothingLeft(&since_watch);
  }

  OwnShm own_shm_;      // first: this test's /dev/shm is its own (private_shm.h)
  ShmJanitor janitor_;  // sees /dev/shm before anything of ours exists
  fs::path dir_;
  int domain_ = testDomain(11);
};

// The logs of a run (bridges, agents, simulator), to print beside a failed check.
std::string logs(const fs::path& run) {
  std::string s;
  for (const auto& e : fs::directory_iterator(run / "logs")) {
    const std::string name = e.path().filename().string();
    if (name.rfind("bridge_", 0) == 0 || name.rfind("agent_", 0) == 0 || name == "sim.log") {
      s += "--- " + e.path().filename().string() + "\n" + readFile(e.path());
    }
  }
  return s;
}

// The shipped scenario (GNSS lost at 10 s, lockstep) for 60 s, run directly and through the PX4 stand-ins of the given
// releases, same seed: 50 s without GNSS show a loop that does not hold (the shipped 120 s add test time, not
// evidence). "Directly" is the in-process closed loop, which a direct lockstep launch equals bit for bit
// (tests/integration/test_dds_swarm.cpp) and which costs no processes.
// A run through the autopilots passed as cohesively as the direct loop (d_NB within the tolerance, no collision, one
// group), with every agent answering throughout (no dead agent, no bridge restart), and every vehicle engaged once on
// its bridge's request (`engaged`: the event's text, "OFFBOARD on request" or "GUIDED on request").
void expectAsCohesiveAsDirectAndEveryVehicleEngaged(const LaunchedRun& run, double d_direct,
                                                    const std::string& engaged) {
  EXPECT_EQ(run.status, 0) << run.summary << logs(run.dir);
  EXPECT_NEAR(jsonNumber(run.summary, "mean_neighbor_distance_m"), d_direct, kDnbToleranceM);
  EXPECT_EQ(jsonNumber(run.summary, "collisions"), 0.0);
  EXPECT_EQ(jsonNumber(run.summary, "groups"), 1.0);
  EXPECT_EQ(jsonNumber(run.summary, "bridge_restarts"), 0.0);
  const std::string sim_summary = readFile(run.dir / "sim_summary.json");
  EXPECT_EQ(jsonNumber(sim_summary, "agent_dead_events"), 0.0) << sim_summary;
  const std::string events = readFile(run.dir / "events.csv");
  std::size_t count = 0;
  for (std::size_t at = events.find(engaged); at != std::string::npos; at = events.find(engaged, at + 1)) ++count;
  EXPECT_EQ(count, static_cast<std::size_t>(jsonNumber(run.summary, "uav_count"))) << events;
  // AND with the autopilots' estimators modelled (vehicle.estimator, issue #43), no vehicle left SWA's control after
  // GNSS was lost at 10 s: each bridge fed its agent's estimate as external odometry from then on
  EXPECT_EQ(events.find("control_lost"), std::string::npos) << events;
  const std::string bridge_log = readFile(run.dir / "logs" / "bridge_0.log");
  EXPECT_NE(bridge_log.find("feeding the agent's estimate to"), std::string::npos) << bridge_log;
}

void Px4SwarmTest::expectAsCohesiveAsDirect(const std::string& scenario, const std::vector<px4::Release>& releases) {
  const double d_direct = inProcessDnb(scenario, {"duration_s=60"});
  for (const px4::Release release : releases) {
    const std::string name = px4::releaseName(release);
    SCOPED_TRACE(scenario + " through PX4 " + name);
    const LaunchedRun px4 = launch(scenario, "px4", {"duration_s=60", "vehicle.px4_release=" + name}, name);
    ASSERT_NE(px4.status, -1) << "still running after " << kRunBoundS << " s";
    const double d_px4 = jsonNumber(px4.summary, "mean_neighbor_distance_m");
    RecordProperty(scenario + "_d_nb_px4_" + name + "_m", std::to_string(d_px4));
    std::cout << scenario << ": d_NB direct " << d_direct << " m, through PX4 " << name << " " << d_px4 << " m\n";
    // THEN both complete with the same verdict, and through PX4 the swarm is as cohesive, every agent answering
    // throughout; AND every vehicle went to OFFBOARD on its bridge's request, once: the bridge heard the release's
    // vehicle_status (its layout, its topic name), or it would never have seen the vehicle armed and in offboard
    expectAsCohesiveAsDirectAndEveryVehicleEngaged(px4, d_direct, "OFFBOARD on request");
    const std::string bridge_log = readFile(px4.dir / "logs" / "bridge_0.log");
    EXPECT_NE(bridge_log.find("PX4 " + name), std::string::npos) << bridge_log;
  }
  expectNothingLeft();
}

// The same through the ArduPilot stand-ins: cmd_vel in ENU, GUIDED through the mode_switch service.
void Px4SwarmTest::expectThroughArdupilotAsCohesiveAsDirect(const std::string& scenario, DiscoveryObserver* observer) {
  SCOPED_TRACE(scenario + " through ArduPilot");
  const double d_direct = inProcessDnb(scenario, {"duration_s=60"});
  // With the observer (the 4-UAV run) it is recorded too.
  const LaunchedRun ap = launch(scenario, "ardupilot", {"duration_s=60"}, "", observer != nullptr);
  ASSERT_NE(ap.status, -1) << "still running after " << kRunBoundS << " s";
  const double d_ap = jsonNumber(ap.summary, "mean_neighbor_distance_m");
  RecordProperty(scenario + "_d_nb_ardupilot_m", std::to_string(d_ap));
  std::cout << scenario << ": d_NB direct " << d_direct << " m, through ArduPilot " << d_ap << " m\n";
  // THEN it passes as cohesively as the direct loop, every agent answering throughout; AND every vehicle went to
  // GUIDED once, on its bridge's mode_switch request (answered: the bridge logs the reply)
  expectAsCohesiveAsDirectAndEveryVehicleEngaged(ap, d_direct, "GUIDED on request");
  const int n = static_cast<int>(jsonNumber(ap.summary, "uav_count"));
  const std::string bridge_log = readFile(ap.dir / "logs" / "bridge_0.log");
  EXPECT_NE(bridge_log.find("ArduPilot namespace 'ap/v1'"), std::string::npos) << bridge_log;
  EXPECT_NE(bridge_log.find("ArduPilot answered the GUIDED request: switched"), std::string::npos) << bridge_log;
  if (observer != nullptr) {
    // AND bridge I touched only vehicle I's topics and services and UAV I's, and no agent touched ArduPilot's
    const VehicleTopics vehicle = ardupilotTopics([](int i) { return dds::topics::apNamespace(i); });
    const std::vector<Endpoint> endpoints = observer->log().endpoints();
    const std::string table = endpointTable(endpoints);
    const std::vector<std::string> bridges = auditBridges(endpoints, n, vehicle);
    EXPECT_TRUE(bridges.empty()) << bridges.front() << "\n" << table;
    const std::vector<std::string> agents = auditIsolation(endpoints);
    EXPECT_TRUE(agents.empty()) << agents.front() << "\n" << table;
    // AND the recording holds what the agents read from their bridges: re-run in-process on it, every recorded
    // command comes out again, byte for byte (swa_replay --check). The agent's cmd_vel writer keeps only its newest
    // sample (KEEP_LAST 1, idl/runtime/dds/profiles.xml): a recorder that falls behind on a loaded host misses one
    // now and then (CI: 1 of 6000 for two UAVs), which the replay produces without a recorded twin. That is the
    // recording's gap, not a difference.
    const replay::RecordedRun recorded = replay::readRecordedRun((ap.dir / "run.mcap").string(), std::nullopt, false);
    ASSERT_TRUE(recorded.scenario_yaml);
    const std::vector<replay::UavCheck> checks =
        replay::checkRun(recorded, sim::parseRecordedScenario(*recorded.scenario_yaml, "run.mcap", {}).agent);
    ASSERT_EQ(checks.size(), static_cast<std::size_t>(n)) << replay::formatChecks(checks);
    for (const replay::UavCheck& c : checks) {
      EXPECT_GT(c.recorded, 0u) << replay::formatChecks(checks);
      EXPECT_EQ(c.identical, c.recorded) << replay::formatChecks(checks);
      EXPECT_EQ(c.differing, 0u) << replay::formatChecks(checks);
      EXPECT_EQ(c.not_replayed, 0u) << replay::formatChecks(checks);
    }
  }
  expectNothingLeft();
}

TEST_F(Px4SwarmTest, FourUavsFlyThroughArdupilotAsCohesivelyAsDirectEachBridgeOnItsOwnVehicle) {
  std::unique_ptr<DiscoveryObserver> observer = observeQuietDomain(domain_, "swa_test_ardupilot_observer");
  ASSERT_TRUE(observer) << "no quiet DDS domain found";
  expectThroughArdupilotAsCohesiveAsDirect("dropout_4.yaml", observer.get());
}

TEST_F(Px4SwarmTest, EightUavsFlyThroughArdupilotAsCohesivelyAsDirect) {
  expectThroughArdupilotAsCohesiveAsDirect("dropout_8.yaml", nullptr);
}

TEST_F(Px4SwarmTest, FourUavsFlyThroughEveryPx4ReleaseAsCohesivelyAsDirect) {
  expectAsCohesiveAsDirect("dropout_4.yaml", {std::begin(px4::kReleases), std::end(px4::kReleases)});
}

// With the simulator's own GNSS these runs differ between releases only in vehicle_status, which decides the
// engagement: 8 UAVs through the two current ones
// (v1.15's 8-UAV run measured 9.7601 m against 9.7603 m through v1.16 and v1.17).
TEST_F(Px4SwarmTest, EightUavsFlyThroughPx4V116AndV117AsCohesivelyAsDirect) {
  expectAsCohesiveAsDirect("dropout_8.yaml", {px4::Release::kV1_16, px4::Release::kV1_17});
}

// Without the external odometry (vehicle.odometry = off: swa_px4_bridge --odometry off) a real autopilot leaves SWA's
// control a few seconds after GNSS is lost (issue #43): PX4 once EKF2 has dead-reckoned for EKF2_NOAID_TOUT (5 s after
// the last fix), ArduPilot once EKF3 has had no position for 7 s and the EKF failsafe has waited 1 s. 4 UAVs, GNSS lost
// at 10 s, 25 s: every vehicle leaves within that time of the loss plus 1 s, and the verdict FAILs and says why.
std::vector<std::pair<double, double>> eventsOf(const fs::path& run, int uav, const std::string& what);

void expectEveryVehicleLeavesSwaWithoutOdometry(const LaunchedRun& run, double leave_after_s, const char* how) {
  EXPECT_EQ(run.status, 1) << run.summary;
  const std::string reasons = run.summary.substr(std::min(run.summary.size(), run.summary.find("verdict_reasons")));
  for (int i = 0; i < 4; ++i) {
    SCOPED_TRACE("UAV " + std::to_string(i));
    const auto lost = eventsOf(run.dir, i, how);
    ASSERT_EQ(lost.size(), 1u) << readFile(run.dir / "events.csv");
    EXPECT_GE(lost[0].first, 10.0 + leave_after_s - 1.0);
    EXPECT_LE(lost[0].first, 10.0 + leave_after_s + 1.0);
    EXPECT_NE(reasons.find("UAV " + std::to_string(i) + " out of SWA's control"), std::string::npos) << reasons;
  }
}

TEST_F(Px4SwarmTest, WithoutOdometryEveryPx4LeavesOffboardAfterEkf2NoaidToutAndTheRunFails) {
  const LaunchedRun run = launch("dropout_4.yaml", "px4", {"duration_s=25", "vehicle.odometry=off"}, "no_odometry");
  ASSERT_NE(run.status, -1) << "still running after " << kRunBoundS << " s";
  expectEveryVehicleLeavesSwaWithoutOdometry(run, 5.0, "local velocity invalid");
  expectNothingLeft();
}

TEST_F(Px4SwarmTest, WithoutOdometryEveryArdupilotLandsOnItsEkfFailsafeAndTheRunFails) {
  const LaunchedRun run =
      launch("dropout_4.yaml", "ardupilot", {"duration_s=25", "vehicle.odometry=off"}, "no_odometry");
  ASSERT_NE(run.status, -1) << "still running after " << kRunBoundS << " s";
  expectEveryVehicleLeavesSwaWithoutOdometry(run, 8.0, "EKF failsafe");
  expectNothingLeft();
}

// The largest change of one UAV's commanded velocity per second of its stamps [m/s^2] between consecutive cmd_vel
// samples of a recording answering IMU samples in [from_s, to_s). Per second, so that a sample the recorder missed
// (cmd_vel is KEEP_LAST 1) spreads its change over two steps instead of looking like a jump.
double largestCommandRate(const replay::UavRecording& uav, double from_s, double to_s) {
  msg::VelocitySetpointPubSubType type;
  std::optional<std::pair<double, agent::Vec2>> previous;
  double largest = 0.0;
  for (const replay::Payload& p : uav.commands) {
    eprosima::fastrtps::rtps::SerializedPayload_t payload(static_cast<std::uint32_t>(p.size()));
    std::memcpy(payload.data, p.data(), p.size());
    payload.length = static_cast<std::uint32_t>(p.size());
    msg::VelocitySetpoint m;
    if (!type.deserialize(&payload, &m)) continue;
    const double t = static_cast<double>(m.answered_stamp_ns()) * 1e-9;
    const agent::Vec2 v(m.vx_mps(), m.vy_mps());
    if (previous && t >= from_s && t < to_s && t > previous->first) {
      largest = std::max(largest, (v - previous->second).norm() / (t - previous->first));
    }
    previous = std::make_pair(t, v);
  }
  return largest;
}

// 4 anchored agents whose GNSS comes from their (simulated) autopilots (`vehicle`, named `name` in the bridges' logs),
// lost from 10 s to 20 s of 30.
void Px4SwarmTest::expectGnssLostAndRegainedThroughTheBridges(const std::string& vehicle, const std::string& name) {
  const std::vector<std::string> sets = {"duration_s=30", "gnss.dropout_start_s=10", "gnss.dropout_end_s=20",
                                         "agent.mode=anchored"};
  std::vector<std::string> autopilot_sets = sets;
  autopilot_sets.emplace_back("vehicle.gnss_source=autopilot");
  const LaunchedRun run = launch("dropout_4.yaml", vehicle, autopilot_sets, "gnss", true);
  ASSERT_NE(run.status, -1) << "still running after " << kRunBoundS << " s";
  // THEN the run passes as cohesively as the in-process loop with the simulator's own GNSS
  EXPECT_EQ(run.status, 0) << run.summary << logs(run.dir);
  const double d_direct = inProcessDnb("dropout_4.yaml", sets);
  EXPECT_NEAR(jsonNumber(run.summary, "mean_neighbor_distance_m"), d_direct, kDnbToleranceM);
  EXPECT_EQ(jsonNumber(run.summary, "collisions"), 0.0);
  // AND every bridge forwarded a valid fix, then the loss, then the regain, each once
  const std::string valid_text = "GNSS from " + name + " valid", lost_text = "GNSS from " + name + " LOST";
  for (int i = 0; i < 4; ++i) {
    const std::string log = readFile(run.dir / "logs" / ("bridge_" + std::to_string(i) + ".log"));
    const std::size_t valid = log.find(valid_text);
    const std::size_t lost = log.find(lost_text);
    const std::size_t regained = valid == std::string::npos ? valid : log.find(valid_text, valid + 1);
    EXPECT_NE(valid, std::string::npos) << log;
    EXPECT_NE(lost, std::string::npos) << log;
    EXPECT_NE(regained, std::string::npos) << log;
    EXPECT_TRUE(valid < lost && lost < regained) << log;
    EXPECT_EQ(log.find(lost_text, lost + 1), std::string::npos) << log;
    // AND it fed its agent's estimate to the autopilot while GNSS was lost, and stopped when it returned, the
    // autopilot flying on its own GNSS again: never out of SWA's control (issue #43)
    const std::size_t feeding = log.find("feeding the agent's estimate to " + name);
    const std::size_t stopped = log.find("stopped: the agent has GNSS again");
    EXPECT_NE(feeding, std::string::npos) << log;
    EXPECT_NE(stopped, std::string::npos) << log;
    EXPECT_LT(feeding, stopped) << log;
  }
  EXPECT_EQ(readFile(run.dir / "events.csv").find("control_lost"), std::string::npos)
      << readFile(run.dir / "events.csv");
  // AND the commanded velocity does not jump when GNSS returns (the feed stops, the anchored hold returns, blended in
  // over anchor.regain_ramp_s): from 0.5 s before to 1 s after it, no UAV's command changes faster than it did
  // before, with GNSS and while the estimate was fed. Measured through PX4 with the accelerometer source (issue #44):
  // 7-38 m/s^2 there against 19-77 before (the formation's own steps at each scan); with the hold switched on at once
  // (regain_ramp_s 0) UAVs 1 and 3 stepped 65 and 29 m/s^2 within 0.5 s of the regain, more than they ever did before
  // (38 and 19). A window reaching 2.5 s past the regain (as before issue #44) also takes in formation steps that
  // have nothing to do with it: UAV 0 stepped 64 m/s^2 at 22.3 s with the ramp, after the ramp had ended.
  const replay::RecordedRun recorded = replay::readRecordedRun((run.dir / "run.mcap").string(), std::nullopt, false);
  ASSERT_EQ(recorded.uavs.size(), 4u);
  for (const auto& [uav, r] : recorded.uavs) {
    const double before = largestCommandRate(r, 2.0, 19.5), regain = largestCommandRate(r, 19.5, 21.0);
    std::cout << "UAV " << uav << ": largest command change before the regain " << before << " m/s^2, around it "
              << regain << " m/s^2\n";
    EXPECT_GT(before, 0.0) << "UAV " << uav;
    EXPECT_LE(regain, before) << "UAV " << uav;
  }
  expectNothingLeft();
}

TEST_F(Px4SwarmTest, GnssLostAndRegainedByTheVehiclesReachesTheAgentsThroughTheBridges) {
  expectGnssLostAndRegainedThroughTheBridges("px4", "PX4");
}

// ArduPilot's stand-ins send no fix at all while GNSS is lost, as ArduPilot does while its GPS is unhealthy: the
// bridges tell the loss from the silence.
TEST_F(Px4SwarmTest, GnssLostAndRegainedByArdupilotReachesTheAgentsThroughTheBridges) {
  expectGnssLostAndRegainedThroughTheBridges("ardupilot", "ArduPilot");
}

// The valid GNSS fixes an agent read (swa/uav<I>/gnss, as its bridge sent them): times [s] and east, north [m].
std::vector<std::pair<double, agent::Vec2>> validFixes(const replay::UavRecording& uav) {
  msg::GnssFixPubSubType type;
  std::vector<std::pair<double, agent::Vec2>> out;
  for (const replay::InputSample& s : uav.inputs) {
    if (s.input != replay::Input::kGnss) continue;
    eprosima::fastrtps::rtps::SerializedPayload_t payload(static_cast<std::uint32_t>(s.payload.size()));
    std::memcpy(payload.data, s.payload.data(), s.payload.size());
    payload.length = static_cast<std::uint32_t>(s.payload.size());
    msg::GnssFix m;
    if (type.deserialize(&payload, &m) && m.valid()) {
      out.emplace_back(static_cast<double>(s.stamp_ns) * 1e-9, agent::Vec2(m.x_m(), m.y_m()));
    }
  }
  return out;
}

// Issue #46: PX4 re-sets its EKF2 origin in flight (a new GPS origin, SET_GPS_GLOBAL_ORIGIN) and re-bases x, y on it,
// so what it sends jumps by the origins' difference. 4 anchored agents (they hold their places by GNSS) with GNSS from
// the PX4 stand-ins, lost from 15 s to 20 s of 25; every stand-in moves its origin 500 m east at 8 s, GNSS valid then.
TEST_F(Px4SwarmTest, APx4OriginMovedInFlightReachesNoAgentAsAJump) {
  const std::vector<std::string> sets = {"duration_s=25", "gnss.dropout_start_s=15", "gnss.dropout_end_s=20",
                                         "agent.mode=anchored"};
  std::vector<std::string> px4_sets = sets;
  px4_sets.insert(px4_sets.end(), {"vehicle.gnss_source=autopilot", "vehicle.px4_origin_shift_at_s=8",
                                   "vehicle.px4_origin_shift_east_m=500"});
  const LaunchedRun run = launch("dropout_4.yaml", "px4", px4_sets, "origin", /*record=*/true);
  ASSERT_NE(run.status, -1) << "still running after " << kRunBoundS << " s";
  // THEN the run passes as cohesively as the in-process loop, whose GNSS has no origin to move
  EXPECT_EQ(run.status, 0) << run.summary << logs(run.dir);
  const double d_direct = inProcessDnb("dropout_4.yaml", sets);
  EXPECT_NEAR(jsonNumber(run.summary, "mean_neighbor_distance_m"), d_direct, kDnbToleranceM);
  EXPECT_EQ(jsonNumber(run.summary, "collisions"), 0.0);
  EXPECT_EQ(jsonNumber(run.summary, "groups"), 1.0);
  // AND every stand-in moved its origin at 8 s, and every bridge logged the change once, before GNSS was lost,
  // brought the positions back and counted it in its summary
  const std::string sim_log = readFile(run.dir / "logs" / "sim.log");
  const std::string change = "PX4 moved its local origin (ref_timestamp ";
  const std::string where =
      " -> 8000000, 500.00 m east, 0.00 m north of the first): positions brought into the first "
      "origin's frame";
  for (int i = 0; i < 4; ++i) {
    SCOPED_TRACE("UAV " + std::to_string(i));
    EXPECT_NE(sim_log.find("t = 8.00 s: UAV " + std::to_string(i) + ": PX4 stand-in px4_" + std::to_string(i) +
                           " moved its local origin 500.00 m east, 0.00 m north"),
              std::string::npos)
        << sim_log;
    const std::string log = readFile(run.dir / "logs" / ("bridge_" + std::to_string(i) + ".log"));
    const std::size_t at = log.find(change);
    ASSERT_NE(at, std::string::npos) << log;
    EXPECT_EQ(log.find(change, at + 1), std::string::npos) << log;
    EXPECT_NE(log.find(where, at), std::string::npos) << log;
    EXPECT_LT(at, log.find("GNSS from PX4 LOST")) << log;
    const std::string summary = readFile(run.dir / "logs" / ("bridge_" + std::to_string(i) + "_summary.json"));
    EXPECT_EQ(jsonNumber(summary, "origin_changes"), 1.0) << summary;
    EXPECT_EQ(jsonNumber(summary, "unusable_reference"), 0.0) << summary;
  }
  // AND no agent's GNSS jumped: consecutive valid fixes (10 Hz; not across the outage) of a UAV step at most 5 m, where
  // the origin moved 500 m: 5 m/s at most is 0.5 m a fix, and the difference of two fixes' noise (0.5 m std per
  // coordinate each) exceeds 4.5 m with a chance of exp(-4.5^2) = 2e-9 a pair (measured: at most 2.7 m); the fixes on
  // either side of 8 s were valid
  const replay::RecordedRun recorded = replay::readRecordedRun((run.dir / "run.mcap").string(), std::nullopt, false);
  ASSERT_EQ(recorded.uavs.size(), 4u);
  for (const auto& [uav, r] : recorded.uavs) {
    const std::vector<std::pair<double, agent::Vec2>> fixes = validFixes(r);
    double largest = 0.0;
    bool before = false, after = false;
    for (std::size_t k = 1; k < fixes.size(); ++k) {
      if (fixes[k].first - fixes[k - 1].first > 0.15) continue;
      largest = std::max(largest, (fixes[k].second - fixes[k - 1].second).norm());
      before = before || (fixes[k].first >= 7.5 && fixes[k].first < 8.0);
      after = after || (fixes[k].first >= 8.0 && fixes[k].first < 8.5);
    }
    std::cout << "UAV " << uav << ": " << fixes.size() << " valid fixes, largest step " << largest << " m\n";
    EXPECT_GT(fixes.size(), 100u) << "UAV " << uav;
    EXPECT_LT(largest, 5.0) << "UAV " << uav;
    EXPECT_TRUE(before && after) << "UAV " << uav;
  }
  expectNothingLeft();
}

// events.csv rows of one UAV whose text contains `what`: their times [s] and values.
std::vector<std::pair<double, double>> eventsOf(const fs::path& run, int uav, const std::string& what) {
  std::vector<std::pair<double, double>> out;
  std::istringstream in(readFile(run / "events.csv"));
  std::string line;
  std::getline(in, line);  // header: t_s,kind,uav,other_uav,value,text
  while (std::getline(in, line)) {
    std::vector<std::string> f;
    std::istringstream row(line);
    for (std::string x; f.size() < 5 && std::getline(row, x, ',');) f.push_back(x);
    if (f.size() == 5 && std::stoi(f[2]) == uav && line.find(what) != std::string::npos) {
      out.emplace_back(std::stod(f[0]), std::stod(f[4]));
    }
  }
  return out;
}

// The failsafe whose event text contains `what` came once, to `victim` alone, after `after_s`, at the first step past
// `limit_s` of silence, and the launcher restarted that bridge (and no agent) once. `at_s` gets its time.
void expectTheVictimsFailsafeAndItsBridgeRestarted(const fs::path& out, int victim, const std::string& what,
                                                   double after_s, double limit_s, double& at_s) {
  const auto failsafe = eventsOf(out, victim, what);
  ASSERT_EQ(failsafe.size(), 1u) << readFile(out / "events.csv") << logs(out);
  at_s = failsafe[0].first;
  EXPECT_GT(failsafe[0].first, after_s);
  EXPECT_GT(failsafe[0].second, limit_s);
  EXPECT_LE(failsafe[0].second, limit_s + 0.0101);  // detected at the first step past the limit
  for (int i = 0; i < 4; ++i) {
    if (i == victim) continue;
    EXPECT_TRUE(eventsOf(out, i, what).empty()) << "UAV " << i;
  }
  const std::string summary = readFile(out / "summary.json");
  EXPECT_EQ(jsonNumber(summary, "bridge_restarts"), 1.0) << summary;
  EXPECT_EQ(jsonNumber(summary, "agent_restarts"), 0.0) << summary;
  EXPECT_NE(readFile(out / "logs" / "restarts.csv").find(",bridge_" + std::to_string(victim) + ","), std::string::npos);
}

// The mean speed of `uav` over [from_s, to_s] from trajectories.csv (positions every 0.5 s).
double meanSpeed(const fs::path& run, int uav, double from_s, double to_s) {
  std::istringstream in(readFile(run / "trajectories.csv"));
  std::string line;
  std::getline(in, line);  // t_s,uav,x_m,y_m
  std::vector<std::array<double, 3>> track;
  while (std::getline(in, line)) {
    std::array<double, 4> v{};
    std::istringstream row(line);
    std::string x;
    for (double& d : v) {
      std::getline(row, x, ',');
      d = std::stod(x);
    }
    if (static_cast<int>(v[1]) == uav && v[0] >= from_s && v[0] <= to_s) track.push_back({v[0], v[2], v[3]});
  }
  if (track.size() < 2) return std::nan("");
  double path = 0.0;
  for (std::size_t k = 1; k < track.size(); ++k) {
    path += std::hypot(track[k][1] - track[k - 1][1], track[k][2] - track[k - 1][2]);
  }
  return path / (track.back()[0] - track.front()[0]);
}

TEST_F(Px4SwarmTest, AKilledBridgeLetsPx4FailSafeThenItIsRestartedAndTheUavRejoins) {
  constexpr int kVictim = 2;
  constexpr double kComOfLossT = 1.0;
  const fs::path out = dir_ / "kill";
  // GIVEN a 4-UAV run through PX4 in realtime (40 s; in lockstep the simulated time stops while the simulator waits
  // for the killed bridge's answer, so PX4 would never see the heartbeat missing), the launcher restarting a bridge
  // after 2 s (longer than COM_OF_LOSS_T: a faster restart keeps the vehicle in offboard), no gusts, as for ArduPilot
  // below: a held vehicle in the simulator's wind drifts at the gust times the velocity lag, 0.2 m/s at one standard
  // deviation (fresh-clone CI: 0.109 m/s against the bar of 0.1, with the gusts of the seconds the hold fell on)
  std::vector<std::string> args =
      launchArgs("dropout_4.yaml", "px4", out, {"duration_s=40", "clock.mode=realtime", "wind.gust_std=0"});
  args.insert(args.end(), {"--restart-backoff-s", "2"});
  // WHEN its bridge is SIGKILLed once the agent has published its state for t = 15 s
  std::optional<int> status;
  runKillingTheBridge(args, "kill.log", kVictim, 15'000'000'000LL, status);
  ASSERT_FALSE(HasFatalFailure());
  const std::string summary = readFile(out / "summary.json");
  // THEN PX4 (the stand-in) lost the offboard signal: failsafe once its heartbeat was silent for COM_OF_LOSS_T, and
  // that UAV alone; the launcher restarted the bridge
  double lost_s = 0.0;
  expectTheVictimsFailsafeAndItsBridgeRestarted(out, kVictim, "offboard lost", 15.0, kComOfLossT, lost_s);
  ASSERT_FALSE(HasFatalFailure());
  // AND the restarted bridge engaged offboard again: the UAV rejoined
  const auto engaged = eventsOf(out, kVictim, "OFFBOARD on request");
  ASSERT_EQ(engaged.size(), 2u) << readFile(out / "events.csv");
  const double back_s = engaged[1].first;
  EXPECT_GT(back_s, lost_s);
  // AND between the two it held: from 2 s after the loss (the velocity responds with a 1 s lag) it barely moved
  if (back_s - lost_s > 3.0) {
    const double held = meanSpeed(out, kVictim, lost_s + 2.0, back_s);
    EXPECT_LT(held, 0.1) << "mean speed " << held << " m/s while holding";
  }
  // AND the swarm stayed cohesive without a collision
  EXPECT_EQ(*status, 0) << summary << logs(out);
  EXPECT_EQ(jsonNumber(summary, "collisions"), 0.0);
}

TEST_F(Px4SwarmTest, AKilledArdupilotBridgeLetsItsVehicleStopAfterGuidTimeoutThenItRejoins) {
  constexpr int kVictim = 1;
  constexpr double kGuidTimeoutS = 1.0;
  const fs::path out = dir_ / "kill_ap";
  // GIVEN a 4-UAV run through ArduPilot in realtime (30 s), GUID_TIMEOUT 1 s, the launcher restarting a bridge after
  // 6 s (so that the vehicle times out and holds for a while), no gusts (a held vehicle in the simulator's wind
  // drifts at ~0.25 m/s: its hold is a zero-velocity setpoint, not a position hold)
  std::vector<std::string> args = launchArgs("dropout_4.yaml", "ardupilot", out,
                                             {"duration_s=30", "clock.mode=realtime", "wind.gust_std=0",
                                              "vehicle.guid_timeout_s=" + std::to_string(kGuidTimeoutS)});
  args.insert(args.end(), {"--restart-backoff-s", "6"});
  // WHEN its bridge is SIGKILLed once the agent has published its state for t = 12 s
  std::optional<int> status;
  runKillingTheBridge(args, "kill_ap.log", kVictim, 12'000'000'000LL, status);
  ASSERT_FALSE(HasFatalFailure());
  const std::string summary = readFile(out / "summary.json");
  // THEN ArduPilot (the stand-in) stopped the vehicle once cmd_vel was silent for GUID_TIMEOUT, that UAV alone; the
  // launcher restarted the bridge
  double stopped_s = 0.0;
  expectTheVictimsFailsafeAndItsBridgeRestarted(out, kVictim, "GUID_TIMEOUT", 12.0, kGuidTimeoutS, stopped_s);
  ASSERT_FALSE(HasFatalFailure());
  // AND the restarted bridge's commands moved the vehicle again (still in GUIDED: no new request)
  const auto back = eventsOf(out, kVictim, "cmd_vel again");
  ASSERT_EQ(back.size(), 1u) << readFile(out / "events.csv");
  EXPECT_GT(back[0].first, stopped_s);
  EXPECT_EQ(eventsOf(out, kVictim, "GUIDED on request").size(), 1u);
  // AND in between it held: from 2 s after the stop (the velocity responds with a 1 s lag) it barely moved. The
  // back-off is wall time and the simulated world pauses while the simulator itself stalls (a busy host), so the
  // simulated hold can be shorter than the back-off (CI of 30003c1: 1.13 s for a 4 s back-off): judged when long
  // enough to judge.
  if (back[0].first - stopped_s > 3.0) {
    const double held = meanSpeed(out, kVictim, stopped_s + 2.0, back[0].first);
    EXPECT_LT(held, 0.1) << "mean speed " << held << " m/s while holding";
  }
  // AND the swarm stayed cohesive without a collision
  EXPECT_EQ(*status, 0) << summary << logs(out);
  EXPECT_EQ(jsonNumber(summary, "collisions"), 0.0);
}

// A bridge that no longer hears its own shared-memory port says so (swa/dds/deaf_port_watch.h), re-creates its
// participant, and its UAV flies on (issue #46). The race that leaves a port so is rare, so the test makes the state
// directly, as for the simulator and the agent (test_dds_swarm.cpp): the bridge's port files deleted and created again
// under it.
TEST_F(Px4SwarmTest, ABridgeDeafOnItsOwnSharedMemoryPortReCreatesItsParticipantAndItsUavFliesOn) {
  constexpr int kVictim = 1;
  const fs::path out = dir_ / "deaf";
  const fs::path bridge_log = out / "logs" / ("bridge_" + std::to_string(kVictim) + ".log");
  const std::string who = "swa_px4_bridge " + std::to_string(kVictim);
  // GIVEN a 4-UAV run through ArduPilot in realtime (20 s), and UAV 1's agent's state heard here
  auto watch = std::make_unique<StateStampWatch>(domain_, kVictim);
  const ShmJanitor since_watch;
  Child launch(launchArgs("dropout_4.yaml", "ardupilot", out, {"duration_s=20", "clock.mode=realtime"}),
               dir_ / "deaf.log");
  ASSERT_TRUE(watch->waitUntil(5'000'000'000LL, launch)) << readFile(dir_ / "deaf.log") << readFile(bridge_log);
  // ... whose bridge listens on ports of its own
  const int bridge = uavProcessPid(domain_, "swa_px4_bridge", kVictim);
  ASSERT_GT(bridge, 0);
  const std::set<int> ports = listedPorts(readFile(bridge_log), who);
  ASSERT_GE(ports.size(), 2u) << readFile(bridge_log);  // metatraffic and user data
  for (const int port : ports) EXPECT_TRUE(holdsOpen(bridge, lockFileOf(port))) << port;
  EXPECT_LT(deafPortNamed(readFile(bridge_log)), 0) << readFile(bridge_log);
  // WHEN its port files are re-created under it, once the agent has published its state for t = 5 s
  const std::vector<fs::path> made = recreatePortFiles(ports);
  // THEN within a few seconds (it looks every 250 ms) it names one of them and re-creates its participant
  const auto deadline = SteadyClock::now() + std::chrono::seconds(5);
  while (SteadyClock::now() < deadline && deafPortNamed(readFile(bridge_log)) < 0) {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  const std::string log = readFile(bridge_log);
  EXPECT_EQ(ports.count(deafPortNamed(log)), 1u) << log;
  EXPECT_NE(log.find(who + ": deaf on shared-memory port"), std::string::npos) << log;
  EXPECT_NE(log.find("re-creating the participant"), std::string::npos) << log;
  // AND the same bridge process carries the UAV on: its agent's states go on to t = 15 s, the run completes, and the
  // launcher restarted no bridge
  EXPECT_TRUE(watch->waitUntil(15'000'000'000LL, launch)) << log;
  const std::optional<int> status = launch.wait(kRunBoundS);
  removeFiles(made);
  watch.reset();
  ASSERT_TRUE(status) << "swa_launch still running";
  const std::string summary = readFile(out / "summary.json");
  EXPECT_EQ(*status, 0) << summary << logs(out);
  EXPECT_EQ(jsonNumber(summary, "bridge_restarts"), 0.0) << summary;
  expectNothingLeft(&since_watch);
}

TEST_F(Px4SwarmTest, EachBridgeTouchesOnlyItsVehicleAndItsUav) {
  // GIVEN an observer of every endpoint on a quiet domain
  std::unique_ptr<DiscoveryObserver> observer = observeQuietDomain(domain_, "swa_test_px4_observer");
  ASSERT_TRUE(observer) << "no quiet DDS domain found";
  // WHEN a 4-UAV run goes through PX4
  const LaunchedRun run = launch("dropout_4.yaml", "px4", {"duration_s=10"});
  const auto px4Namespace = [](int i) { return dds::topics::px4Namespace(i); };
  waitFor([&] { return auditBridges(observer->log().endpoints(), 4, px4Topics(px4Namespace)).empty(); }, 10.0);
  const std::vector<Endpoint> endpoints = observer->log().endpoints();
  const std::string table = endpointTable(endpoints);
  ASSERT_EQ(run.status, 0) << run.summary;
  // THEN bridge I reads and writes only UAV I's PX4 namespace and SWA topics, every bridge is there, no agent touches
  // PX4, and the agents' isolation holds as in a direct run
  const std::vector<std::string> bridges = auditBridges(endpoints, 4, px4Topics(px4Namespace));
  EXPECT_TRUE(bridges.empty()) << bridges.front() << "\n" << table;
  const std::vector<std::string> agents = auditIsolation(endpoints);
  EXPECT_TRUE(agents.empty()) << agents.front() << "\n" << table;
  const std::vector<std::string> complete = auditAgentEndpoints(endpoints, 4);
  EXPECT_TRUE(complete.empty()) << complete.front() << "\n" << table;
  observer.reset();
  expectNothingLeft();
}

}  // namespace
}  // namespace swa::testing

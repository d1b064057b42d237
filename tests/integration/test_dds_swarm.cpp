// The swarm as processes over Fast DDS: swa_sim + one swa_agent per UAV on a private domain, observed through a
// monitor participant in this test (swa/truth, swa/events) and the files swa_sim writes. Every child is reaped and
// every shared-memory file a killed process leaves is removed on the way out, also when a check fails.

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <mutex>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include <swa/msg/AgentStatePubSubTypes.h>
#include <swa/msg/DetectionsPubSubTypes.h>
#include <swa/msg/ImuPubSubTypes.h>
#include <swa/msg/ScenarioEventPubSubTypes.h>
#include <swa/msg/SensorFramePubSubTypes.h>
#include <swa/msg/SwarmMissionPubSubTypes.h>
#include <swa/msg/SwarmTruthPubSubTypes.h>
#include <swa/msg/VelocitySetpointPubSubTypes.h>

#include "own_ports.h"
#include "private_shm.h"
#include "process_test.h"
#include "resting_imu.h"
#include "swa/agent/agent.h"
#include "swa/agent/feed.h"
#include "swa/dds/options.h"
#include "swa/dds/participant.h"
#include "swa/dds/qos_profiles.h"
#include "swa/dds/sample_queue.h"
#include "swa/dds/topics.h"
#include "swa/sim/scenario_io.h"
#include "swa/sim/world.h"
#include "swa/wire/mission.h"

namespace swa::testing {
namespace {

const std::string kScenario = std::string(SWA_SOURCE_DIR) + "/deploy/scenarios/dropout_4.yaml";
constexpr double kRunBoundS = 120.0;  // wall-clock bound of one simulator run

struct TruthRow {
  long long step = 0;
  long long t_ns = 0;
  int uav = 0;
  double x = 0, y = 0, vx = 0, vy = 0;
};

std::vector<TruthRow> readTruthCsv(const fs::path& p) {
  std::ifstream in(p);
  std::string line;
  std::getline(in, line);  // header
  std::vector<TruthRow> rows;
  while (std::getline(in, line)) {
    std::vector<std::string> f;
    std::stringstream ss(line);
    for (std::string cell; std::getline(ss, cell, ',');) f.push_back(cell);
    if (f.size() < 7) continue;
    TruthRow r;
    r.step = std::stoll(f[0]);
    r.t_ns = std::stoll(f[1]);
    r.uav = std::stoi(f[2]);
    r.x = std::strtod(f[3].c_str(), nullptr);
    r.y = std::strtod(f[4].c_str(), nullptr);
    r.vx = std::strtod(f[5].c_str(), nullptr);
    r.vy = std::strtod(f[6].c_str(), nullptr);
    rows.push_back(r);
  }
  return rows;
}

std::vector<TruthRow> lastStep(const std::vector<TruthRow>& rows) {
  if (rows.empty()) return {};
  const long long last = rows.back().step;
  std::vector<TruthRow> out;
  for (const TruthRow& r : rows) {
    if (r.step == last) out.push_back(r);
  }
  std::sort(out.begin(), out.end(), [](const TruthRow& a, const TruthRow& b) { return a.uav < b.uav; });
  return out;
}

// Mean over UAVs of the mean distance to its two nearest neighbours.
double meanTwoNearest(const std::vector<agent::Vec2>& p) {
  double sum = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    std::vector<double> d;
    for (std::size_t j = 0; j < p.size(); ++j) {
      if (j != i) d.push_back((p[i] - p[j]).norm());
    }
    std::sort(d.begin(), d.end());
    sum += (d.at(0) + d.at(1)) / 2.0;
  }
  return sum / static_cast<double>(p.size());
}

double minSeparation(const std::vector<agent::Vec2>& p) {
  double m = 1e300;
  for (std::size_t i = 0; i < p.size(); ++i) {
    for (std::size_t j = i + 1; j < p.size(); ++j) m = std::min(m, (p[i] - p[j]).norm());
  }
  return m;
}

// The mean distance to the two nearest neighbours (d_NB) and the smallest separation of the UAVs in `rows`.
struct Geometry {
  double d_nb_m = 0.0;
  double min_separation_m = 0.0;
};

Geometry geometryOf(const std::vector<TruthRow>& rows) {
  std::vector<agent::Vec2> p;
  for (const TruthRow& r : rows) p.emplace_back(r.x, r.y);
  const Geometry g{meanTwoNearest(p), minSeparation(p)};
  std::cout << "final d_NB (2 nearest) = " << g.d_nb_m << " m, min separation = " << g.min_separation_m << " m\n";
  return g;
}

// The oracle: the same scenario in one process, samples fed as deploy/programs/batch/closed_loop.cpp does.
std::vector<sim::UavTruth> inProcessFinalTruth(const sim::Scenario& scenario) {
  sim::World world(scenario);
  std::vector<agent::Agent> agents(static_cast<std::size_t>(world.uav_count()), agent::Agent(scenario.agent));
  while (true) {
    for (int i = 0; i < world.uav_count(); ++i) {
      agent::Agent& a = agents[static_cast<std::size_t>(i)];
      const sim::UavSensors& s = world.sensors()[static_cast<std::size_t>(i)];
      if (const auto command = agent::feedInstant(a, s.imu, s.detections, s.gnss)) world.command(i, *command);
    }
    if (world.finished()) break;
    world.step();
  }
  return world.truth();
}

// A participant in this test process that watches what a monitor would: swa/truth, swa/events, swa/uav<i>/state.
class Monitor {
 public:
  // `imu_of`: also read that UAV's swa/uav<I>/imu, the per-topic sensor path (-1: none).
  Monitor(int domain, int uav_count, int imu_of = -1)
      : participant_(std::make_unique<dds::Participant>("swa_test_monitor", domain, dds::resolveProfilesFile())) {
    if (imu_of >= 0) {
      participant_->reader<msg::ImuPubSubType>(dds::topics::imu(imu_of), dds::qos::kSensorReader, imu_.listener());
    }
    for (int i = 0; i < uav_count; ++i) {
      participant_->reader<msg::AgentStatePubSubType>(dds::topics::state(i), dds::qos::kStateReader,
                                                      states_.listener());
    }
    participant_->reader<msg::SwarmTruthPubSubType>(dds::topics::kTruth, dds::qos::kTruthReader, truth_.listener());
    participant_->reader<msg::ScenarioEventPubSubType>(dds::topics::kEvents, dds::qos::kEventReader,
                                                       events_.listener());
  }
  ~Monitor() { participant_.reset(); }

  // Collects what arrived; waits up to `wait` for the first new truth sample.
  void poll(std::chrono::milliseconds wait = std::chrono::milliseconds(0)) {
    truth_.take(wait);
    events_.take();
    states_.take();
    imu_.take();
  }
  // The samples read on swa/uav<imu_of>/imu, in arrival order.
  const std::vector<msg::Imu>& imu() const { return imu_.seen; }
  // AgentState samples of one UAV, in arrival order.
  std::vector<msg::AgentState> states(int uav) const {
    std::vector<msg::AgentState> out;
    for (const msg::AgentState& a : states_.seen) {
      if (a.uav_id() == static_cast<std::uint32_t>(uav)) out.push_back(a);
    }
    return out;
  }
  const std::vector<msg::SwarmTruth>& truth() const { return truth_.seen; }
  const std::vector<msg::ScenarioEvent>& events() const { return events_.seen; }
  int count(msg::EventKind kind, int uav = -2) const {
    return static_cast<int>(std::count_if(events_.seen.begin(), events_.seen.end(), [&](const msg::ScenarioEvent& e) {
      return e.kind() == kind && (uav == -2 || e.uav_id() == uav);
    }));
  }
  // Waits until an event of that kind about that UAV arrived (false if `bound_s` of wall time pass first).
  bool waitForEvent(msg::EventKind kind, int uav, double bound_s) {
    const auto deadline = SteadyClock::now() + std::chrono::duration<double>(bound_s);
    while (SteadyClock::now() < deadline) {
      poll(std::chrono::milliseconds(20));
      if (count(kind, uav) > 0) return true;
    }
    return false;
  }
  // Waits until the simulator's truth reaches `t_s` (false if `bound_s` of wall time pass first).
  bool waitForSimTime(double t_s, double bound_s) {
    const auto deadline = SteadyClock::now() + std::chrono::duration<double>(bound_s);
    while (SteadyClock::now() < deadline) {
      poll(std::chrono::milliseconds(20));
      if (!truth_.seen.empty() && static_cast<double>(truth_.seen.back().header().stamp_ns()) * 1e-9 >= t_s) {
        return true;
      }
    }
    return false;
  }

 private:
  // Declared before the participant, whose listeners push into them: they outlive it.
  Received<msg::SwarmTruth> truth_;
  Received<msg::ScenarioEvent> events_;
  Received<msg::AgentState> states_;
  Received<msg::Imu> imu_;
  std::unique_ptr<dds::Participant> participant_;
};

// One run: the agent configuration exported from the scenario, N agents, the simulator, and the monitor participant.
class SwarmRun : public ProcessRun {
 protected:
  void SetUp() override {
    dir_ = freshTestDir("swa_dds_it");
    domain_ = testDomain();
    useOwnSwarm();  // no sample of another DDS user on this domain can reach the run
  }

  void stopObservers() override { monitor_.reset(); }

  std::vector<std::string> simArgs(const std::vector<std::string>& overrides) const {
    std::vector<std::string> a{SWA_SIM_BINARY, "--scenario", kScenario};
    for (const std::string& o : overrides) {
      a.push_back("--set");
      a.push_back(o);
    }
    return a;
  }

  // Exports the agents' configuration, starts the monitor and `n` agents, then the simulator. `env`: extra
  // environment of the swa_sim / swa_agent processes (not of the monitor in this process).
  void start(const std::vector<std::string>& overrides, const std::vector<std::string>& sim_extra, int n = 4,
             const std::vector<std::string>& env = {}) {
    ASSERT_EQ(exportAgentConfig(simArgs(overrides), dir_), 0) << readFile(dir_ / "export.log");

    monitor_ = std::make_unique<Monitor>(domain_, n, imu_of_);
    for (int i = 0; i < n; ++i) {
      agents_.push_back(std::make_unique<Child>(agentCommand(SWA_AGENT_BINARY, i, domain_, dir_ / "agent.yaml"),
                                                dir_ / ("agent" + std::to_string(i) + ".log"), env));
    }
    std::vector<std::string> args = simArgs(overrides);
    args.insert(args.end(), {"--domain", std::to_string(domain_), "--truth-out", (dir_ / "truth.csv").string(),
                             "--summary-out", (dir_ / "summary.json").string()});
    args.insert(args.end(), sim_extra.begin(), sim_extra.end());
    sim_ = std::make_unique<Child>(args, dir_ / "sim.log", env);
    started_ = SteadyClock::now();
  }

  // Waits for the simulator (bounded), then stops the agents. Returns the simulator's exit status.
  int finish() {
    const std::optional<int> status = sim_->wait(kRunBoundS);
    wall_s_ = std::chrono::duration<double>(SteadyClock::now() - started_).count();
    if (!status) ADD_FAILURE() << "swa_sim still running after " << kRunBoundS << " s: killed";
    monitor_->poll(std::chrono::milliseconds(200));
    for (auto& a : agents_) agent_status_.push_back(a->stop(10.0));
    return status.value_or(-1);
  }

  std::string realtimeFourAgents();

  void lockstepDropout4(const std::vector<std::string>& overrides, double expected_d_nb_m,
                        const std::vector<std::string>& env = {});
  void stopSimulator(const char* clock_mode, bool stall_reported);
  void deafOnItsOwnPort(const std::string& who, const fs::path& log_file, const std::function<pid_t()>& pid);

  std::string logs() const { return runLogs(dir_, agents_.size()); }
  // The UAVs at the last step of the simulator's truth.csv, by id.
  std::vector<TruthRow> finalTruth() const { return lastStep(readTruthCsv(dir_ / "truth.csv")); }
  // The run's last step is the in-process closed loop's bit for bit: positions, and velocities if `velocities`.
  void expectFinalTruthOfTheInProcessLoop(const std::vector<std::string>& overrides, bool velocities) const {
    const std::vector<TruthRow> final_rows = finalTruth();
    const std::vector<sim::UavTruth> ref = inProcessFinalTruth(sim::loadScenario(kScenario, overrides));
    ASSERT_EQ(final_rows.size(), 4u);
    ASSERT_EQ(ref.size(), 4u);
    for (std::size_t i = 0; i < 4; ++i) {
      EXPECT_EQ(final_rows[i].x, ref[i].position_m.x()) << "UAV " << i;
      EXPECT_EQ(final_rows[i].y, ref[i].position_m.y()) << "UAV " << i;
      if (!velocities) continue;
      EXPECT_EQ(final_rows[i].vx, ref[i].velocity_mps.x()) << "UAV " << i;
      EXPECT_EQ(final_rows[i].vy, ref[i].velocity_mps.y()) << "UAV " << i;
    }
  }

  std::unique_ptr<Monitor> monitor_;
  int imu_of_ = -1;  // the UAV whose swa/uav<I>/imu the monitor also reads (Monitor's imu_of)
  std::vector<int> agent_status_;
  SteadyClock::time_point started_;
  double wall_s_ = 0.0;
};

// The paper's GNSS-loss scenario with 4 UAVs, 20 s, as 5 processes in lockstep: checks the run, cohesion (mean
// distance to the 2 nearest neighbours within +-15 % of `expected_d_nb_m`) and bit-equality with the in-process loop.
void SwarmRun::lockstepDropout4(const std::vector<std::string>& overrides, double expected_d_nb_m,
                                const std::vector<std::string>& env) {
  start(overrides, {"--agent-timeout-s", "10"}, 4, env);
  ASSERT_FALSE(HasFatalFailure());
  // WHEN the simulator runs to the end
  const int status = finish();
  ASSERT_EQ(status, 0) << logs();
  const std::string summary = readFile(dir_ / "summary.json");
  std::cout << "lockstep run: " << wall_s_ << " s wall (processes started to sim exit); summary:\n" << summary;
  RecordProperty("wall_s", std::to_string(wall_s_));

  // THEN every agent shut down cleanly on SIGTERM
  for (std::size_t i = 0; i < agent_status_.size(); ++i) EXPECT_EQ(agent_status_[i], 0) << "agent " << i;

  // THEN the run completed with every agent answering every step and no collision
  EXPECT_EQ(jsonNumber(summary, "completed"), 1.0);
  EXPECT_EQ(jsonNumber(summary, "steps"), 2000.0);
  EXPECT_EQ(jsonNumber(summary, "collisions"), 0.0);
  EXPECT_EQ(jsonNumber(summary, "agent_dead_events"), 0.0) << logs();
  EXPECT_EQ(jsonNumber(summary, "applied_commands"), 4.0 * 2001.0);
  // THEN the loop latency of every command was recorded (lockstep has no deadline: nothing is late)
  EXPECT_EQ(jsonNumber(summary, "latency_commands_answered"), 4.0 * 2001.0);
  EXPECT_EQ(jsonNumber(summary, "missing_answers"), 0.0);
  EXPECT_EQ(jsonNumber(summary, "late_commands"), 0.0);
  EXPECT_GT(jsonNumber(summary, "latency_p50_us"), 0.0);

  // THEN the swarm is cohesive at the end
  const std::vector<TruthRow> final_rows = finalTruth();
  ASSERT_EQ(final_rows.size(), 4u);
  EXPECT_EQ(final_rows.front().t_ns, 20'000'000'000LL);
  const Geometry final_geometry = geometryOf(final_rows);
  EXPECT_NEAR(final_geometry.d_nb_m, expected_d_nb_m, 0.15 * expected_d_nb_m);
  EXPECT_GT(final_geometry.min_separation_m, 2.0);

  // THEN the monitor saw the same truth on swa/truth and the events on swa/events
  ASSERT_FALSE(monitor_->truth().empty());
  const msg::SwarmTruth& last = monitor_->truth().back();
  EXPECT_EQ(last.header().stamp_ns(), 20'000'000'000LL);
  ASSERT_EQ(last.uavs().size(), 4u);
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(last.uavs()[i].x_m(), final_rows[i].x);
    EXPECT_EQ(last.uavs()[i].y_m(), final_rows[i].y);
    EXPECT_TRUE(last.uavs()[i].alive());
  }
  EXPECT_EQ(monitor_->count(msg::EVENT_SCENARIO_END), 1);
  EXPECT_EQ(monitor_->count(msg::EVENT_GNSS_LOST), 4);  // all four lose GNSS at 10 s
  EXPECT_EQ(monitor_->count(msg::EVENT_COLLISION), 0);
  EXPECT_EQ(monitor_->count(msg::EVENT_AGENT_DEAD), 0);
  // THEN every agent published its state at 10 Hz of sim time: 201 states for t = 0, 0.1, ..., 20 s (header.seq
  // counts them all). The topic is VOLATILE and the simulator does not wait for this monitor, so the first ones may
  // predate the match; from the first one received on, none is missing.
  for (int i = 0; i < 4; ++i) {
    const std::vector<msg::AgentState> st = monitor_->states(i);
    ASSERT_GE(st.size(), 20u) << "UAV " << i;
    EXPECT_EQ(st.back().header().seq(), 201u) << "UAV " << i;
    EXPECT_EQ(st.back().header().seq() - st.front().header().seq() + 1, st.size()) << "UAV " << i;
    EXPECT_EQ(st.back().header().stamp_ns(), 20'000'000'000LL);
    EXPECT_EQ(st.back().stage(), msg::STAGE_TRACKING) << "UAV " << i;
    EXPECT_TRUE(st.back().frame_valid()) << "UAV " << i;
    EXPECT_GE(st.back().neighbour_ids().size(), 2u) << "UAV " << i;
    EXPECT_EQ(st.back().commands_sent(), 2001u) << "UAV " << i;
    EXPECT_EQ(st.back().rejected_out_of_order() + st.back().rejected_nonfinite(), 0u) << "UAV " << i;
  }
  // THEN, where the monitor read a UAV's swa/uav<I>/imu, the samples travelled there up to the last step, none missing
  // from the first one it matched in time for (with sensor frames nothing is written there)
  if (imu_of_ >= 0) {
    const std::vector<msg::Imu>& imu = monitor_->imu();
    ASSERT_FALSE(imu.empty()) << "nothing on swa/uav" << imu_of_ << "/imu";
    EXPECT_EQ(imu.back().header().stamp_ns(), 20'000'000'000LL);
    EXPECT_EQ(imu.back().header().seq() - imu.front().header().seq() + 1, imu.size());
  }
  // THEN, once our monitor participant is gone too, no process left shared memory behind (a port stays while any
  // participant that ever sent to it is alive, so this is checked after the monitor)
  monitor_.reset();
  const std::string left = shmFilesLeft(janitor_, domain_);
  EXPECT_TRUE(left.empty()) << "a process exited without deleting its DDS entities: " << left;

  // THEN lockstep reproduces the in-process closed loop bit for bit (same scenario, seed, sample order)
  expectFinalTruthOfTheInProcessLoop(overrides, true);
}

TEST_F(SwarmRun, LockstepDropout4AsShippedHoldsTenMetresAndEqualsTheInProcessLoop) {
  // The shipped file uses Gabriel neighbours: the four settle as a rhombus with every edge r = 10 m, so the two
  // nearest of every UAV are at r (closed loop, 20 seeds: d_NB 9.96 m at 120 s).
  lockstepDropout4({"duration_s=20"}, 10.0);
}

TEST_F(SwarmRun, LockstepDropout4K3EqualsTheInProcessLoop) {
  // k nearest with k = 3 and the unweighted fit (the default before issue #10), set on the command line, so the
  // agents' agent.yaml carries a non-default rule: with 4 UAVs each one fits a radius-r circle through all three
  // others, which a planar formation cannot satisfy. For a square of side a the fixed-radius fit balances 2 (a - r)^2 +
  // (a sqrt2 - r)^2, so a = r (2 + sqrt2) / 4 = 8.54 m, -14.6 % from r: the +-15 % band of 10 m would sit on its edge.
  // The run is checked against that equilibrium instead (measured: 8.45 m at 20 s, seed 1, identical in process and
  // over DDS).
  lockstepDropout4({"duration_s=20", "agent.formation.neighbourhood=k_nearest", "agent.k=3",
                    "agent.formation.far_neighbour_weight=1"},
                   10.0 * (2.0 + std::sqrt(2.0)) / 4.0);
}

TEST_F(SwarmRun, LockstepWithALimitedFieldOfViewTurnsAsTheInProcessLoopDoes) {
  // GIVEN 240 deg sensors: every agent commands a yaw rate (issue #26), which travels in cmd_vel (message set 3), and
  // the world turns each UAV, which changes what its sensor sees
  const std::vector<std::string> overrides{"duration_s=20", "mps.fov_deg=240"};
  start(overrides, {"--agent-timeout-s", "10"});
  ASSERT_FALSE(HasFatalFailure());
  ASSERT_EQ(finish(), 0) << logs();
  // THEN the run is the in-process closed loop bit for bit: the yaw rates arrived as computed, and the UAVs turned
  // as they do there (a heading off by one bit would move what the sensors see, and the positions with it)
  expectFinalTruthOfTheInProcessLoop(overrides, true);
  EXPECT_EQ(monitor_->count(msg::EVENT_COLLISION), 0);
  EXPECT_EQ(monitor_->count(msg::EVENT_AGENT_DEAD), 0);
}

TEST_F(SwarmRun, LockstepWithAMissionFliesItAsTheInProcessLoopDoes) {
  // GIVEN a mission every agent holds (issue #45): out north-east at 2.2 m/s, then back to the start at 3 m/s; a
  // 240 deg sensor, so the agents also turn to face each leg
  const std::vector<std::string> overrides{
      "duration_s=20", "mps.fov_deg=240", "mission.start=time",
      "mission.legs=[{velocity_mps: [2, 1], duration_s: 8}, {to_m: [20, 0], speed_mps: 3}]"};
  start(overrides, {"--agent-timeout-s", "10"});
  ASSERT_FALSE(HasFatalFailure());
  ASSERT_EQ(finish(), 0) << logs();
  // THEN the swarm went where the plan ends, 20 m east of where it was, give or take what a plan does not correct
  // (DESIGN §3.6: the response to each leg, here also four UAVs settling into their rhombus and turning their 240 deg
  // sensors; measured in process: (22.7, -3.8) m)
  ASSERT_FALSE(monitor_->truth().empty());
  double east = 0.0, north = 0.0;
  for (int i = 0; i < 4; ++i) {
    east += (monitor_->truth().back().uavs()[i].x_m() - monitor_->truth().front().uavs()[i].x_m()) / 4.0;
    north += (monitor_->truth().back().uavs()[i].y_m() - monitor_->truth().front().uavs()[i].y_m()) / 4.0;
  }
  EXPECT_NEAR(east, 20.0, 6.0);
  EXPECT_NEAR(north, 0.0, 6.0);
  // AND the run is the in-process closed loop bit for bit: the plan is the same in every process
  expectFinalTruthOfTheInProcessLoop(overrides, true);
  EXPECT_EQ(monitor_->count(msg::EVENT_COLLISION), 0);
  EXPECT_EQ(monitor_->count(msg::EVENT_AGENT_DEAD), 0);
}

// The ground's mission changed live (issue #45): swa_mission mid-flight, every agent follows from its next IMU sample;
// a second writer's mission meanwhile is refused and counted, never flown. Realtime: the command comes when it comes.
TEST_F(SwarmRun, RealtimeGroundMissionIsFollowedByEveryAgentAndASecondWritersMissionIsRefused) {
  // GIVEN 4 agents flying a plan east at 2 m/s from 0 s, realtime, 30 s
  start({"duration_s=30", "clock.mode=realtime", "mission.start=time",
         "mission.legs=[{velocity_mps: [2, 0], duration_s: 60}]"},
        {});
  ASSERT_FALSE(HasFatalFailure());
  ASSERT_TRUE(monitor_->waitForSimTime(5.0, 60.0)) << logs();
  // WHEN the ground sends "north at 2 m/s for 8 s" (and stays, the ground's writer)
  Child ground(
      {SWA_MISSION_BINARY, "--leg", "vel:0,2,8", "--expect", "4", "--stay", "--domain", std::to_string(domain_)},
      dir_ / "ground.log");
  const auto sent_by = SteadyClock::now() + std::chrono::seconds(20);
  while (readFile(dir_ / "ground.log").find("acknowledged by every one") == std::string::npos &&
         SteadyClock::now() < sent_by) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  ASSERT_NE(readFile(dir_ / "ground.log").find("acknowledged by every one"), std::string::npos)
      << readFile(dir_ / "ground.log");
  // AND then a second writer, while the ground's is there, sends "west at 2 m/s for 30 s"
  auto rogue = std::make_unique<dds::Participant>("swa_test_rogue", domain_, dds::resolveProfilesFile());
  auto rogue_writer = rogue->writer<msg::SwarmMissionPubSubType>(dds::topics::kMission, dds::qos::kMissionWriter);
  agent::MissionCommand west;
  west.legs = {{agent::MissionCommandLeg::Kind::kVelocity, agent::Vec2(-2, 0), 30.0, 0.0}};
  msg::SwarmMission m = wire::toMsg(west, 0, 1);
  const auto matched_by = SteadyClock::now() + std::chrono::seconds(20);
  while (rogue_writer.matched() < 4 && SteadyClock::now() < matched_by) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  ASSERT_EQ(rogue_writer.matched(), 4);
  ASSERT_TRUE(rogue_writer.write(m));
  EXPECT_TRUE(rogue_writer.waitForAcknowledgments(10.0));
  ASSERT_EQ(finish(), 0) << logs();
  EXPECT_EQ(ground.stop(10.0), 0) << readFile(dir_ / "ground.log");

  // THEN every agent flew the ground's mission from the IMU sample after the one it arrived behind (one IMU period,
  // 10 ms), and only that one
  const std::regex flown(
      "mission 1 from the ground flown from IMU stamp (\\d+) ns \\(it arrived after the sample of "
      "(\\d+) ns\\)");
  double flown_at_s = 0.0;
  for (int i = 0; i < 4; ++i) {
    const std::string log = readFile(dir_ / ("agent" + std::to_string(i) + ".log"));
    std::smatch match;
    ASSERT_TRUE(std::regex_search(log, match, flown)) << log;
    const long long at = std::stoll(match[1]), after = std::stoll(match[2]);
    EXPECT_GT(at, after) << log;
    EXPECT_LE(at - after, 10'000'000LL) << log;
    EXPECT_EQ(std::distance(std::sregex_iterator(log.begin(), log.end(), flown), std::sregex_iterator()), 1) << log;
    flown_at_s = std::max(flown_at_s, static_cast<double>(at) * 1e-9);
    // AND refused the second writer's, counted
    EXPECT_NE(log.find("REFUSED a mission on swa/swarm/mission from a second writer"), std::string::npos) << log;
    EXPECT_NE(log.find("2 received, 1 flown, 0 that could not be flown, 0 unreadable, 1 from a second writer refused"),
              std::string::npos)
        << log;
  }
  // AND the swarm went where that plan ends: 2 m/s east until the command, then 16 m north (give or take the
  // formation settling in and the response to each leg, DESIGN §3.6), not 60 m west
  ASSERT_FALSE(monitor_->truth().empty());
  double east = 0.0, north = 0.0;
  for (int i = 0; i < 4; ++i) {
    east += (monitor_->truth().back().uavs()[i].x_m() - monitor_->truth().front().uavs()[i].x_m()) / 4.0;
    north += (monitor_->truth().back().uavs()[i].y_m() - monitor_->truth().front().uavs()[i].y_m()) / 4.0;
  }
  EXPECT_NEAR(east, 2.0 * flown_at_s, 5.0) << "command flown from " << flown_at_s << " s";
  EXPECT_NEAR(north, 16.0, 5.0);
  const std::vector<TruthRow> final_rows = finalTruth();
  ASSERT_EQ(final_rows.size(), 4u);
  EXPECT_NEAR(geometryOf(final_rows).d_nb_m, 10.0, 1.5);
  EXPECT_EQ(monitor_->count(msg::EVENT_COLLISION), 0);
  EXPECT_EQ(monitor_->count(msg::EVENT_AGENT_DEAD), 0);
}

TEST_F(SwarmRun, LockstepOverUdpOnlyEqualsTheInProcessLoop) {
  // GIVEN the network transport profile (SWA_TRANSPORT=network: UDPv4 only, as between hosts or containers), where
  // lost and repaired datagrams can reorder topics
  // THEN the same bit-exact run as over shared memory
  lockstepDropout4({"duration_s=20"}, 10.0, {"SWA_TRANSPORT=network"});
}

TEST_F(SwarmRun, LockstepWithEachSampleOnItsOwnTopicEqualsTheInProcessLoop) {
  // GIVEN direct vehicles and SWA's detections, where the simulator would bundle a step's samples in one SensorFrame,
  // told by SWA_SENSOR_FRAMES=0 to write them on swa/uav<I>/{imu,detections,gnss} as bridges and real sensors do
  imu_of_ = 0;
  // THEN the same bit-exact run as with frames
  // (and lockstepDropout4 checks that UAV 0's IMU did travel on swa/uav0/imu)
  lockstepDropout4({"duration_s=20"}, 10.0, {"SWA_SENSOR_FRAMES=0"});
}

TEST_F(SwarmRun, StalledAgentIsDeclaredDeadAndRejoinsCrashedAgentStaysDead) {
  // GIVEN a 90 s lockstep run with a short agent timeout
  start({"duration_s=90"}, {"--agent-timeout-s", "0.3"});
  ASSERT_FALSE(HasFatalFailure());
  ASSERT_TRUE(monitor_->waitForSimTime(3.0, 60.0)) << logs();
  // WHEN agent 2 stalls (SIGSTOP) until the simulator has declared it dead, then resumes
  agents_[2]->signal(SIGSTOP);
  const bool declared = monitor_->waitForEvent(msg::EVENT_AGENT_DEAD, 2, 30.0);
  agents_[2]->signal(SIGCONT);
  ASSERT_TRUE(declared) << logs();
  // WHEN agent 3 crashes (SIGKILL)
  agents_[3]->signal(SIGKILL);
  // THEN the world goes on and completes
  const int status = finish();
  ASSERT_EQ(status, 0) << logs();
  const std::string summary = readFile(dir_ / "summary.json");
  std::cout << summary;
  // THEN both were declared dead, the stalled one rejoined, the crashed one is dead at the end and its UAV
  // fell back to the failsafe. On a busy host a 0.3 s timeout may also be missed by an agent that only ran late
  // (in CI once every live agent did, right after the stalled one resumed): such an agent rejoins, so the exact
  // claim is about the order of each agent's events, not their number.
  EXPECT_GE(monitor_->count(msg::EVENT_AGENT_DEAD, 2), 1) << logs();
  EXPECT_GE(monitor_->count(msg::EVENT_AGENT_REJOINED, 2), 1) << logs();
  for (int uav = 0; uav < 4; ++uav) {
    // Each agent's deaths and rejoins alternate, starting with a death; only the crashed one ends dead.
    std::vector<msg::EventKind> life;
    for (const msg::ScenarioEvent& e : monitor_->events()) {
      const bool about_life = e.kind() == msg::EVENT_AGENT_DEAD || e.kind() == msg::EVENT_AGENT_REJOINED;
      if (about_life && e.uav_id() == uav) life.push_back(e.kind());
    }
    for (std::size_t k = 0; k < life.size(); ++k) {
      const msg::EventKind expected = k % 2 == 0 ? msg::EVENT_AGENT_DEAD : msg::EVENT_AGENT_REJOINED;
      EXPECT_EQ(life[k], expected) << "UAV " << uav << " event " << k;
    }
    EXPECT_EQ(life.size() % 2 == 1, uav == 3) << "UAV " << uav << ": " << life.size() << " event(s)\n" << logs();
  }
  EXPECT_GE(monitor_->count(msg::EVENT_FAILSAFE, 3), 1);
  EXPECT_EQ(nlohmann::json::parse(summary)["dead_at_end"], nlohmann::json::array({3})) << summary;
  ASSERT_FALSE(monitor_->truth().empty());
  EXPECT_FALSE(monitor_->truth().back().uavs().at(3).alive());
  EXPECT_EQ(agent_status_[2], 0);  // the stalled agent still shuts down cleanly
}

// In lockstep the simulator publishes no step until every live agent has answered: while it waits for one, the
// others hear nothing with their writers matched, which their silence watches took for a broken channel (issue #46:
// in a secure launch through PX4 the simulator waited 60 s at step 0 for one agent, the others re-created their
// participants every 6 s, and one UAV ended on failsafe). Now the waiting simulator repeats its clock tick once a
// second, and an agent that hears a tick twice knows the world waits (agent/node/world_pause.h).
// The stopped agent itself may need the product's own recovery once it runs again, and the agent timeout gives it
// that (a 15 s timeout failed once in 3 suite runs and once in 12 repeats: the agent answered more than 6 s after its
// 9 s stop). Stopped past the 4 s lease, it is forgotten and found again (announcements every 1 s); stopped past Fast
// DDS's 1 s port check, its shared-memory port may have been re-created under it (swa/dds/shm_ports.h), and it hears
// nothing until its silence watch re-creates its participant (6 s, then about 1 s to match; the step's samples come
// as the writers' history, TRANSIENT_LOCAL). So: 9 s stopped + 6 s + a few seconds to match, within 30 s.
TEST_F(SwarmRun, AgentsWaitingWithTheLockstepSimulatorForAStoppedAgentKeepTheirParticipants) {
  // GIVEN a lockstep run of 4 agents whose simulator waits up to 30 s for an answer
  const std::vector<std::string> overrides{"duration_s=20"};
  start(overrides, {"--agent-timeout-s", "30"});
  ASSERT_FALSE(HasFatalFailure());
  ASSERT_TRUE(monitor_->waitForSimTime(3.0, 60.0)) << logs();
  // WHEN agent 2 is stopped for 9 s: longer than the agents' silence limit (6 s), shorter than the agent timeout
  agents_[2]->signal(SIGSTOP);
  std::this_thread::sleep_for(std::chrono::seconds(9));
  agents_[2]->signal(SIGCONT);
  // THEN the run completes with no agent dead
  ASSERT_EQ(finish(), 0) << logs();
  EXPECT_EQ(monitor_->count(msg::EVENT_AGENT_DEAD), 0) << logs();
  // AND none of the three that waited re-created its participant: they knew the world waited
  for (const int i : {0, 1, 3}) {
    const std::string log = readFile(dir_ / ("agent" + std::to_string(i) + ".log"));
    EXPECT_EQ(log.find("re-creating the participant"), std::string::npos) << "agent " << i << ":\n" << log;
  }
  // (said, so that repeated runs show how often the stopped agent needed its own recovery)
  const bool recreated = readFile(dir_ / "agent2.log").find("re-creating the participant") != std::string::npos;
  std::printf("the stopped agent %s its participant\n", recreated ? "re-created" : "kept");
  // AND the run is still the in-process closed loop bit for bit: the wait changed nothing but the wall time
  expectFinalTruthOfTheInProcessLoop(overrides, true);
}

// Issue #11: a second `swa_agent --id 1` in the same swarm started without a word, and any program could write a UAV's
// cmd_vel. Now the younger agent refuses to run (exit 3) and the older one logs it; the simulator applies the
// commands of one writer per UAV and refuses another's while the first is active.
TEST_F(SwarmRun, SecondAgentWithTheSameIdIsRefusedAndAForeignCommanderIsIgnored) {
  // GIVEN a rogue in this process that will answer every IMU sample of UAV 2 at once with a full-speed command, once
  // told to. It joins before the run: its readers of truth and events make the simulator wait for it before step 0
  // (--wait-monitors 2, with the test's monitor). Joining mid-run, it sometimes heard no frame and no command of it
  // reached the simulator before the lockstep run was over (beside a CPU hog: 20 s simulated in 3.5 s of wall time).
  std::atomic<bool> answering{false};
  std::atomic<int> rogue_commands{0};
  auto rogue = std::make_unique<dds::Participant>("swa_test_rogue", domain_, dds::resolveProfilesFile());
  auto rogue_cmd = rogue->writer<msg::VelocitySetpointPubSubType>(dds::topics::cmdVel(2), dds::qos::kCommandWriter);
  std::mutex rogue_mutex;
  // (the simulator writes UAV 2's IMU samples in its frames)
  rogue->reader<msg::SensorFramePubSubType>(dds::topics::sensors(2), dds::qos::kFrameReader, [&](msg::SensorFrame&& f) {
    if (!answering) return;
    const std::lock_guard<std::mutex> lock(rogue_mutex);
    for (const msg::Imu& imu : f.imu_sample()) {
      msg::VelocitySetpoint sp;
      sp.header().stamp_ns(imu.header().stamp_ns());
      sp.uav_id(2);
      sp.vx_mps(2.0);
      sp.answered_stamp_ns(imu.header().stamp_ns());
      sp.answered_seq(imu.header().seq());
      if (rogue_cmd.write(sp)) ++rogue_commands;
    }
  });
  rogue->reader<msg::SwarmTruthPubSubType>(dds::topics::kTruth, dds::qos::kTruthReader, [](msg::SwarmTruth&&) {});
  rogue->reader<msg::ScenarioEventPubSubType>(dds::topics::kEvents, dds::qos::kEventReader,
                                              [](msg::ScenarioEvent&&) {});
  // AND a lockstep run of the 4-UAV scenario, 2 s along (UAV 2's own agent has been commanding it since step 0)
  const std::vector<std::string> overrides{"duration_s=20"};
  start(overrides, {"--agent-timeout-s", "10", "--wait-monitors", "2"});
  ASSERT_FALSE(HasFatalFailure());
  ASSERT_TRUE(monitor_->waitForSimTime(2.0, 60.0)) << logs();

  // WHEN the rogue starts answering
  answering = true;
  // AND a second agent with id 1 starts in the same swarm
  Child twin(agentCommand(SWA_AGENT_BINARY, 1, domain_, dir_ / "agent.yaml"), dir_ / "twin.log");
  // THEN the second agent refuses to run, saying why
  const std::optional<int> twin_status = twin.wait(20.0);
  const std::string twin_log = readFile(dir_ / "twin.log");
  EXPECT_EQ(twin_status.value_or(-1), 3) << twin_log;
  EXPECT_NE(twin_log.find("REFUSING to run: another swa_agent 1"), std::string::npos) << twin_log;
  // AND the simulator refuses the rogue's commands and says so
  const auto refused_rogue = [&] {
    return readFile(dir_ / "sim.log").find("a second writer on swa/uav2/cmd_vel") != std::string::npos;
  };
  EXPECT_TRUE(waitFor(refused_rogue, 20.0)) << rogue_commands.load() << " rogue command(s) written\n" << logs();
  rogue.reset();

  // THEN the run completes as if neither had been there: the simulator refused the rogue's commands, and the run is
  // still the in-process closed loop bit for bit
  ASSERT_EQ(finish(), 0) << logs();
  const std::string summary = readFile(dir_ / "summary.json");
  EXPECT_GT(jsonNumber(summary, "refused_commands"), 0.0) << summary;
  EXPECT_GE(jsonNumber(summary, "refused_writers"), 1.0) << summary;
  EXPECT_EQ(jsonNumber(summary, "command_handovers"), 0.0) << summary;
  EXPECT_EQ(jsonNumber(summary, "agent_dead_events"), 0.0) << logs();
  EXPECT_NE(readFile(dir_ / "agent1.log").find("a second swa_agent 1"), std::string::npos) << logs();
  expectFinalTruthOfTheInProcessLoop(overrides, false);
}

// Two simulators in one swarm would publish two worlds to the same agents. The younger refuses to run; the older says
// so, though the younger is gone again within a poll or two of it.
TEST_F(SwarmRun, SecondSimulatorInTheSameSwarmIsRefusedAndTheFirstSaysSo) {
  // GIVEN a simulator waiting for its agents
  std::vector<std::string> args = simArgs({});
  args.insert(args.end(), {"--domain", std::to_string(domain_), "--startup-timeout-s", "60"});
  Child first(args, dir_ / "sim1.log");
  ASSERT_TRUE(
      waitFor([&] { return readFile(dir_ / "sim1.log").find("waiting for 4 agent(s)") != std::string::npos; }, 20.0))
      << readFile(dir_ / "sim1.log");
  // WHEN a second one starts in the same swarm
  Child second(args, dir_ / "sim2.log");
  // THEN it refuses to run, saying why
  const std::optional<int> status = second.wait(20.0);
  const std::string second_log = readFile(dir_ / "sim2.log");
  EXPECT_EQ(status.value_or(-1), 1) << second_log;
  EXPECT_NE(second_log.find("swa_sim: REFUSING to run: another swa_sim (pid " + std::to_string(first.pid())),
            std::string::npos)
      << second_log;
  // AND the first names it and keeps waiting
  const std::string named = "swa_sim: a second swa_sim (pid " + std::to_string(second.pid()) + " on host ";
  EXPECT_TRUE(waitFor([&] { return readFile(dir_ / "sim1.log").find(named) != std::string::npos; }, 5.0))
      << readFile(dir_ / "sim1.log");
  EXPECT_FALSE(first.wait(0.0)) << readFile(dir_ / "sim1.log");
  first.stop();
}

TEST_F(SwarmRun, SecondAgentWithTheSameIdInAnotherSwarmIsNotATwin) {
  // GIVEN agent 1 running in swarm A
  Child first(agentCommand(SWA_AGENT_BINARY, 1, domain_), dir_ / "first.log");
  // WHEN agent 1 of another swarm starts on the same domain
  const std::string other = "other-" + std::to_string(::getpid());
  Child second(agentCommand(SWA_AGENT_BINARY, 1, domain_), dir_ / "second.log", {"SWA_SWARM=" + other});
  // THEN both keep running (3 s: discovery takes well under a second here), and neither calls the other a twin
  EXPECT_FALSE(second.wait(3.0)) << readFile(dir_ / "second.log");
  EXPECT_FALSE(first.wait(0.0)) << readFile(dir_ / "first.log");
  EXPECT_EQ(second.stop(), 0);
  EXPECT_EQ(first.stop(), 0);
  EXPECT_EQ(readFile(dir_ / "first.log").find("a second swa_agent"), std::string::npos) << readFile(dir_ / "first.log");
  EXPECT_EQ(readFile(dir_ / "second.log").find("REFUSING"), std::string::npos) << readFile(dir_ / "second.log");
}

TEST_F(SwarmRun, AgentWithoutASimulatorSaysWhatItIsWaitingFor) {
  // GIVEN agent 1 alone in its swarm: no simulator
  const fs::path log = dir_ / "agent1.log";
  Child agent(agentCommand(SWA_AGENT_BINARY, 1, domain_), log);
  // WHEN no sample comes for 5 s
  // THEN it says so once, and that nothing matched its endpoints (instead of staying silent like a healthy agent)
  const std::string expected =
      "swa_agent 1: no IMU sample 5 s after connecting; matched: 0 reader(s) of swa/uav1/cmd_vel, 0 writer(s) of "
      "swa/uav1/imu, 0 of swa/uav1/detections, 0 of swa/uav1/gnss";
  EXPECT_TRUE(waitFor([&] { return readFile(log).find(expected) != std::string::npos; }, 15.0)) << readFile(log);
  // AND what it waits for, on which domain and in which swarm (issue #30: a hand-started agent beside a launched run
  // never connects unless its SWA_SWARM matches)
  const std::string waits =
      "swa_agent 1: it waits for a simulator (swa_sim) or an autopilot bridge writing UAV 1's "
      "samples on DDS domain " +
      std::to_string(domain_) + ", in ";
  EXPECT_NE(readFile(log).find(waits), std::string::npos) << readFile(log);
  EXPECT_NE(readFile(log).find("start this agent with that SWA_SWARM"), std::string::npos) << readFile(log);
  // AND it keeps waiting, and stops cleanly
  EXPECT_FALSE(agent.wait(0.0)) << readFile(log);
  EXPECT_EQ(agent.stop(), 0) << readFile(log);
}

// Issue #11: stopping the simulator for 2 s declared every healthy agent dead (realtime). Stopped for 5 s here (beyond
// the DDS lease): that can also break a shared-memory channel between the simulator and an agent for good while
// discovery stays matched (seen in CI: one agent never got a sample again); the agent then re-creates its participant
// after 6 s without a sample (agent/node/silence_watch.h), but the simulator has declared it dead by then, and this
// test fails. In lockstep the agents' answers reach the stopped simulator's queue and complete the step when it
// continues, so a stall there usually costs nothing and is not always seen; only realtime must report it. On the
// default transport, as users run it (issue #46): a stop longer than Fast DDS 2.9's 1 s port health check gets the
// simulator's own shared-memory port re-created by a sender, and now and then the simulator keeps listening on the
// deleted one; it then re-creates its participant (sim_ports.h, healDeafness), and the wait for its endpoints to match
// again counts as its own stall, not as the agents' silence.
void SwarmRun::stopSimulator(const char* clock_mode, bool stall_reported) {
  // GIVEN a run with the default 1 s agent timeout
  start({"duration_s=12", clock_mode}, {});
  ASSERT_FALSE(HasFatalFailure());
  ASSERT_TRUE(monitor_->waitForSimTime(4.0, 60.0)) << logs();
  // WHEN the simulator itself is stopped for 5 s (SIGSTOP), then continued
  sim_->signal(SIGSTOP);
  std::this_thread::sleep_for(std::chrono::seconds(5));
  sim_->signal(SIGCONT);
  // THEN the run completes with no agent declared dead, and the simulator reports its own stall
  ASSERT_EQ(finish(), 0) << logs();
  EXPECT_EQ(monitor_->count(msg::EVENT_AGENT_DEAD), 0) << logs();
  const std::string summary = readFile(dir_ / "summary.json");
  if (!stall_reported) return;
  EXPECT_GE(jsonNumber(summary, "stalls"), 1.0) << summary;
  EXPECT_GE(jsonNumber(summary, "stalled_s"), 4.5) << summary;
}

// A simulator stopped beyond the DDS lease once never reached an agent again while its writers stayed matched
// (silence_watch.h). An agent that had samples and gets none for 6 s from a writer that stays matched
// re-creates its participant; a writer that is gone (unmatched) is no reason to.
TEST_F(SwarmRun, AgentWhoseSamplesStopWhileTheirWriterStaysMatchedReconnects) {
  // GIVEN agent 1 alone, and a writer of its IMU samples in this process
  const fs::path log = dir_ / "agent1.log";
  Child agent(agentCommand(SWA_AGENT_BINARY, 1, domain_), log);
  auto source = std::make_unique<dds::Participant>("swa_test_imu_source", domain_, dds::resolveProfilesFile());
  dds::Writer<msg::Imu> imu = source->writer<msg::ImuPubSubType>(dds::topics::imu(1), dds::qos::kSensorWriter);
  ASSERT_TRUE(waitFor([&] { return imu.matched() > 0; }, 30.0)) << readFile(log);
  // WHEN it writes 1 s of samples at 100 Hz, then nothing, while it stays matched
  for (std::uint32_t k = 0; k < 100; ++k) {
    msg::Imu m = restingImu(1, static_cast<agent::StampNs>(k) * 10'000'000, k + 1);
    imu.write(m);
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  const auto silent_from = SteadyClock::now();
  ASSERT_TRUE(waitFor([&] { return readFile(log).find("first IMU sample") != std::string::npos; }, 5.0))
      << readFile(log);
  // THEN after 6 s without a sample the agent re-creates its participant, and says why
  const std::string why = "swa_agent 1: no sample on swa/uav1/imu for";
  ASSERT_TRUE(waitFor([&] { return readFile(log).find(why) != std::string::npos; }, 20.0)) << readFile(log);
  EXPECT_GE(std::chrono::duration<double>(SteadyClock::now() - silent_from).count(), 6.0);
  // WHEN the writer goes away (unmatched): THEN no further reconnection in the next 10 s
  source.reset();
  const auto reconnections = [&] {
    const std::string text = readFile(log);
    int n = 0;
    for (std::size_t at = text.find("re-creating"); at != std::string::npos; at = text.find("re-creating", at + 1)) ++n;
    return n;
  };
  const int after_first = reconnections();
  std::this_thread::sleep_for(std::chrono::seconds(10));
  EXPECT_EQ(reconnections(), after_first) << readFile(log);
  EXPECT_EQ(agent.stop(), 0) << readFile(log);
}

// The same for SWA's own detections, which come at their sensor rate even when empty (issue #46: an agent of a secure
// launch through ArduPilot got its IMU from the bridge but no detection from the simulator after the first, and its
// UAV left SWA's control): silent for 6 s while IMU samples arrive and their writer stays matched, the agent re-creates
// its participant.
TEST_F(SwarmRun, AgentWhoseDetectionsStopWhileItsImuFlowsReconnects) {
  // GIVEN agent 1 alone, and writers of its IMU samples and of its detections in this process
  const fs::path log = dir_ / "agent1.log";
  Child agent(agentCommand(SWA_AGENT_BINARY, 1, domain_), log);
  auto source = std::make_unique<dds::Participant>("swa_test_sensor_source", domain_, dds::resolveProfilesFile());
  dds::Writer<msg::Imu> imu = source->writer<msg::ImuPubSubType>(dds::topics::imu(1), dds::qos::kSensorWriter);
  dds::Writer<msg::Detections> detections =
      source->writer<msg::DetectionsPubSubType>(dds::topics::detections(1), dds::qos::kDetectionsGnssWriter);
  ASSERT_TRUE(waitFor([&] { return imu.matched() > 0 && detections.matched() > 0; }, 30.0)) << readFile(log);
  // WHEN it writes IMU samples at 100 Hz for 10 s, with (empty) detection sets at 10 Hz for the first second only
  const std::string why = "swa_agent 1: no sample on swa/uav1/detections for";
  const auto t0 = SteadyClock::now();
  for (std::uint32_t k = 0; k < 1000 && readFile(log).find(why) == std::string::npos; ++k) {
    const agent::StampNs stamp = static_cast<agent::StampNs>(k) * 10'000'000;
    if (k < 100 && k % 10 == 0) {
      msg::Detections d;
      d.header().stamp_ns(stamp);
      d.header().seq(k / 10 + 1);
      d.observer_id(1);
      detections.write(d);
    }
    msg::Imu m = restingImu(1, stamp, k + 1);
    imu.write(m);
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  // THEN 6 s or more after the last detection set the agent re-creates its participant, and says why
  ASSERT_TRUE(waitFor([&] { return readFile(log).find(why) != std::string::npos; }, 5.0)) << readFile(log);
  EXPECT_GE(std::chrono::duration<double>(SteadyClock::now() - t0).count(), 7.0);
  EXPECT_NE(readFile(log).find("while IMU samples arrive and 1 writer(s) of it stay matched"), std::string::npos)
      << readFile(log);
  source.reset();
  EXPECT_EQ(agent.stop(), 0) << readFile(log);
}

// A process that no longer hears its own shared-memory port says so (swa/dds/deaf_port_watch.h), re-creates its
// participant, and the run goes on with no agent declared dead (issue #46). The race in Fast DDS 2.9 that leaves it
// there is rare (1 realtime run in 6 with five 2 s stops of the simulator, here), so the test makes the same state
// directly: it deletes the process's port
// files and creates files of the same names again, as a sender re-creating them would. It plants files in /dev/shm:
// in the /dev/shm of its own every SwarmRun has (private_shm.h), a test beside it never counts them. `who` is the
// process's name in its log, `log` its log file, `pid` its process id.
void SwarmRun::deafOnItsOwnPort(const std::string& who, const fs::path& log_file, const std::function<pid_t()>& pid) {
  // GIVEN a realtime run of 4 agents, 3 s in
  start({"duration_s=15", "clock.mode=realtime"}, {});
  ASSERT_FALSE(HasFatalFailure());
  ASSERT_TRUE(monitor_->waitForSimTime(3.0, 30.0)) << logs();
  EXPECT_EQ(readFile(log_file).find("deaf on shared-memory port"), std::string::npos) << logs();
  const std::set<int> ports = listedPorts(readFile(log_file), who);
  ASSERT_GE(ports.size(), 2u) << readFile(log_file);  // metatraffic and user data
  // ... and they are its own: it holds their exclusive-read lock files open, no other process of the run has them open
  std::vector<pid_t> others{sim_->pid()};
  for (const auto& a : agents_) others.push_back(a->pid());
  for (const int port : ports) {
    EXPECT_TRUE(holdsOpen(pid(), lockFileOf(port))) << port;
    for (const pid_t other : others) {
      if (other == pid()) continue;
      EXPECT_FALSE(holdsOpen(other, lockFileOf(port))) << port << " held by " << other;
    }
  }
  // WHEN its port files are re-created under it
  const std::vector<fs::path> made = recreatePortFiles(ports);
  // THEN within a few seconds (it looks every 250 ms) it names one of them, and only those
  const auto deadline = SteadyClock::now() + std::chrono::seconds(5);
  std::string log;
  while (SteadyClock::now() < deadline && deafPortNamed(log) < 0) {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    log = readFile(log_file);
  }
  const int named = deafPortNamed(log);
  ASSERT_GE(named, 0) << log;
  EXPECT_EQ(ports.count(named), 1u) << log;
  // AND it re-creates its participant, and the run completes with nobody declared dead
  EXPECT_NE(log.find("re-creating the participant"), std::string::npos) << log;
  const int status = finish();
  removeFiles(made);
  ASSERT_EQ(status, 0) << logs();
  EXPECT_EQ(monitor_->count(msg::EVENT_AGENT_DEAD), 0) << logs();
}

TEST_F(SwarmRun, SimulatorDeafOnItsOwnSharedMemoryPortReCreatesItsParticipantAndTheRunGoesOn) {
  deafOnItsOwnPort("swa_sim", dir_ / "sim.log", [this] { return sim_->pid(); });
  if (HasFatalFailure()) return;
  // AND every endpoint matched again before it stepped on, which the summary counts
  EXPECT_NE(readFile(dir_ / "sim.log").find("every endpoint matched again"), std::string::npos) << logs();
  EXPECT_GE(jsonNumber(readFile(dir_ / "summary.json"), "reconnections"), 1.0) << readFile(dir_ / "summary.json");
}

// The same for an agent: before its first sample, no silence watch can tell that nothing reaches it.
TEST_F(SwarmRun, AgentDeafOnItsOwnSharedMemoryPortReCreatesItsParticipantAndTheRunGoesOn) {
  deafOnItsOwnPort("swa_agent 1", dir_ / "agent1.log", [this] { return agents_.at(1)->pid(); });
}

TEST_F(SwarmRun, StoppedSimulatorBlamesNoAgentInRealtime) { stopSimulator("clock.mode=realtime", true); }
TEST_F(SwarmRun, StoppedSimulatorBlamesNoAgentInLockstep) { stopSimulator("clock.mode=lockstep", false); }

// One realtime run of RealtimeFourAgentsTwentySecondsCohesiveAndEveryCommandAnswered: every check. Returns the
// summary.
std::string SwarmRun::realtimeFourAgents() {
  // GIVEN the shipped 4-UAV scenario, 20 s, in realtime mode at speed 1 (one step = 10 ms of wall time)
  start({"duration_s=20", "clock.mode=realtime"}, {});
  if (HasFatalFailure()) return "";
  // WHEN the simulator runs to the end
  const int status = finish();
  EXPECT_EQ(status, 0) << logs();
  const std::string summary = readFile(dir_ / "summary.json");
  std::cout << summary;
  if (status != 0) return summary;

  // THEN it ran: at least 20 s of wall time after discovery (realtime is never faster), every agent kept answering,
  // no collision
  EXPECT_EQ(jsonNumber(summary, "completed"), 1.0);
  EXPECT_EQ(jsonNumber(summary, "steps"), 2000.0);
  EXPECT_GE(jsonNumber(summary, "wall_time_s"), 19.95);
  EXPECT_EQ(jsonNumber(summary, "agent_dead_events"), 0.0) << logs();
  EXPECT_GT(jsonNumber(summary, "applied_commands"), 4.0 * 1900.0);
  EXPECT_EQ(jsonNumber(summary, "collisions"), 0.0);
  EXPECT_EQ(monitor_->count(msg::EVENT_SCENARIO_END), 1);
  EXPECT_EQ(monitor_->count(msg::EVENT_AGENT_DEAD), 0);
  for (std::size_t i = 0; i < agent_status_.size(); ++i) EXPECT_EQ(agent_status_[i], 0) << "agent " << i;

  // THEN it is cohesive: d_NB within +-10 % of r (Gabriel as shipped) and nobody closer than 2 m. Realtime is not
  // deterministic, so this is the band, not a value.
  const std::vector<TruthRow> final_rows = finalTruth();
  EXPECT_EQ(final_rows.size(), 4u);
  if (final_rows.size() == 4u) {
    EXPECT_EQ(final_rows.front().t_ns, 20'000'000'000LL);
    const Geometry final_geometry = geometryOf(final_rows);
    EXPECT_NEAR(final_geometry.d_nb_m, 10.0, 1.0);
    EXPECT_GT(final_geometry.min_separation_m, 2.0);
  }

  // THEN every IMU sample after the start handshake (steps 1 .. 2000: step 0 only starts the clock once every agent
  // has answered it) was judged and answered. No startup allowance is needed for missing answers: the clock starts
  // only once every agent has closed the loop, and a sample or command not yet matched the other way is kept by the
  // TRANSIENT_LOCAL writers (agent commands 100 deep = 1 s, sensors 1000 deep) and delivered on matching, so a slow
  // start would make the first answers late, not missing. A missing answer means a lost command or a stalled agent.
  const double judged = jsonNumber(summary, "latency_commands_judged");
  EXPECT_EQ(judged, 4.0 * 2000.0);
  EXPECT_EQ(jsonNumber(summary, "latency_commands_answered"), judged);
  EXPECT_EQ(jsonNumber(summary, "missing_answers"), 0.0) << summary;
  return summary;
}

TEST_F(SwarmRun, RealtimeFourAgentsTwentySecondsCohesiveAndEveryCommandAnswered) {
  // What holds on any host, however busy: every command answered, no agent declared dead, cohesion. How late the
  // answers are (the late fraction, the loop latency) depends on the host's load: that is the benchmark's
  // (bench_dds, BENCHMARKS.md "Loop latency").
  const std::string summary = realtimeFourAgents();
  if (HasFailure()) return;
  std::cout << "late fraction " << jsonNumber(summary, "late_fraction") << ", simulator step lag p99 "
            << jsonNumber(summary, "step_lag_p99_us") << " us, loop latency p50 "
            << jsonNumber(summary, "latency_p50_us") << " us (not judged here)\n";
}

// ---- Bad input: clear error, exit 2, nothing started -------------------------------------------------------------

class BadInput : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = freshTestDir("swa_dds_bad"); }
  void TearDown() override { fs::remove_all(dir_); }

  // Exit status and everything the process printed.
  std::pair<int, std::string> run(const std::vector<std::string>& argv, const std::vector<std::string>& env = {}) {
    const fs::path log = dir_ / "out.log";
    Child c(argv, log, env);
    const std::optional<int> status = c.wait(30.0);
    return {status.value_or(-1), readFile(log)};
  }

  OwnShm own_shm_;  // first: this test's /dev/shm is its own (private_shm.h)
  ShmJanitor janitor_;
  fs::path dir_;
  int domain_ = testDomain(5);  // reserved: nothing of another test's may be counted as ours
  std::string domain_arg_ = std::to_string(domain_);
};

TEST_F(BadInput, MalformedScenarioMakesTheSimulatorExitWithAClearError) {
  const fs::path bad = dir_ / "bad.yaml";
  std::ofstream(bad) << "uav_count: -3\nduration_s: [1, 2]\nfrobnicate: 1\n";
  const auto [status, out] = run({SWA_SIM_BINARY, "--scenario", bad.string(), "--domain", domain_arg_});
  EXPECT_EQ(status, 2) << out;
  for (const char* needle : {"invalid scenario", "uav_count", "duration_s", "frobnicate"}) {
    EXPECT_NE(out.find(needle), std::string::npos) << needle << " missing from:\n" << out;
  }
  const auto [status2, out2] = run({SWA_SIM_BINARY, "--scenario", (dir_ / "missing.yaml").string()});
  EXPECT_EQ(status2, 2) << out2;
  EXPECT_NE(out2.find("missing.yaml"), std::string::npos) << out2;
  const auto [status3, out3] = run({SWA_SIM_BINARY, "--scenario", kScenario, "--set", "duration_s=-1"});
  EXPECT_EQ(status3, 2) << out3;
  EXPECT_NE(out3.find("duration_s"), std::string::npos) << out3;
  const auto [status4, out4] = run({SWA_SIM_BINARY, "--scenario", kScenario, "--domain", "999"});
  EXPECT_EQ(status4, 2) << out4;
  EXPECT_NE(out4.find("--domain"), std::string::npos) << out4;
  EXPECT_EQ(run({SWA_SIM_BINARY, "--help"}).first, 0);
  EXPECT_TRUE(ofDomain(janitor_.zombies(), domain_).empty());
}

TEST_F(BadInput, BadDeploymentEnvironmentIsAClearErrorNotACrash) {
  // Every node validates SWA_TRANSPORT / SWA_DISCOVERY_SERVER / SWA_SECURITY_DIR when it creates its participant.
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases{
      {{"SWA_TRANSPORT=shm"}, "SWA_TRANSPORT 'shm'"},
      {{"SWA_TRANSPORT=discovery-server"}, "needs SWA_DISCOVERY_SERVER"},
      {{"SWA_TRANSPORT=discovery-server", "SWA_DISCOVERY_SERVER=localhost"}, "'localhost' is not IPv4:PORT"},
      {{"SWA_DISCOVERY_SERVER=127.0.0.1:11811"}, "SWA_TRANSPORT is local"},
      {{"SWA_SECURITY_DIR=" + (dir_ / "nowhere").string()}, "swa_agent_1/permissions.p7s"}};
  for (const auto& [env, needle] : cases) {
    const auto [status, out] = run({SWA_AGENT_BINARY, "--id", "1", "--domain", domain_arg_}, env);
    EXPECT_EQ(status, 1) << env.front() << ":\n" << out;  // a DDS failure, not a signal (134 = abort)
    EXPECT_NE(out.find(needle), std::string::npos) << needle << " missing from:\n" << out;
    const auto [sim_status, sim_out] = run({SWA_SIM_BINARY, "--scenario", kScenario, "--domain", domain_arg_}, env);
    EXPECT_EQ(sim_status, 1) << env.front() << ":\n" << sim_out;
  }
  EXPECT_TRUE(ofDomain(janitor_.zombies(), domain_).empty());
}

TEST_F(BadInput, BadIdMakesTheAgentExitWithAClearError) {
  for (const std::vector<std::string>& args : std::vector<std::vector<std::string>>{{SWA_AGENT_BINARY, "--id", "-1"},
                                                                                    {SWA_AGENT_BINARY, "--id", "uav3"},
                                                                                    {SWA_AGENT_BINARY, "--id", "99999"},
                                                                                    {SWA_AGENT_BINARY}}) {
    const auto [status, out] = run(args);
    EXPECT_EQ(status, 2) << out;
    EXPECT_NE(out.find("--id"), std::string::npos) << out;
  }
  const auto [status, out] = run({SWA_AGENT_BINARY, "--id", "1", "--set", "formation.k=0", "--set", "nope=1"});
  EXPECT_EQ(status, 2) << out;
  EXPECT_NE(out.find("formation.k"), std::string::npos) << out;
  EXPECT_NE(out.find("nope"), std::string::npos) << out;
  const auto [status2, out2] = run({SWA_AGENT_BINARY, "--id", "1", "--config", (dir_ / "missing.yaml").string()});
  EXPECT_EQ(status2, 2) << out2;
  EXPECT_EQ(run({SWA_AGENT_BINARY, "--help"}).first, 0);
  EXPECT_TRUE(ofDomain(janitor_.zombies(), domain_).empty());
}

}  // namespace
}  // namespace swa::testing

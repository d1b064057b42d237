// swa_launch end to end: it starts swa_sim, one swa_agent per UAV and swa_monitor on a private domain, supervises
// them and exits with the monitor's verdict. Checked from the outside: exit status, the monitor's summary.json, the
// logs, the restart record, no process left on the domain and no /dev/shm file left behind.

#include <signal.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <swa/msg/AgentStatePubSubTypes.h>
#include <swa/msg/ScenarioEventPubSubTypes.h>

#include "../integration/launch_support.h"
#include "../integration/own_ports.h"
#include "../integration/private_shm.h"
#include "../integration/process_test.h"
#include "closed_loop.h"
#include "recorded_run.h"
#include "replay_check.h"
#include "swa/agent/config_io.h"
#include "swa/app/version.h"
#include "swa/dds/options.h"
#include "swa/dds/participant.h"
#include "swa/dds/qos_profiles.h"
#include "swa/dds/topics.h"
#include "swa/recording/recording.h"
#include "swa/sim/scenario_io.h"

namespace swa::testing {
namespace {

const std::string kScenario = std::string(SWA_SOURCE_DIR) + "/deploy/scenarios/dropout_4.yaml";
const std::string kLaunch = SWA_LAUNCH_BINARY;

class LaunchTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = freshTestDir("swa_launch_test", /*per_test=*/true);
    swarm_ = useOwnSwarm();  // the launcher takes it from the environment; this test's observers join it
  }
  void TearDown() override {
    for (int pid : processesOnDomain(domain_)) ::kill(pid, SIGKILL);  // only after a failed check
    if (!HasFailure()) fs::remove_all(dir_);
  }

  std::vector<std::string> launchArgs(const std::vector<std::string>& extra) const {
    std::vector<std::string> a{
        kLaunch,       "--scenario", kScenario, "--out", (dir_ / "out").string(), "--domain", std::to_string(domain_),
        "--timeout-s", "150"};
    a.insert(a.end(), extra.begin(), extra.end());
    return a;
  }

  // The state of the swarm after the launcher exited: nothing of ours may be left.
  // `since` (default: the fixture's) names the files that existed before the launcher started: a participant of the
  // test itself may leave port files that a killed agent kept referenced, which are the test's to clean, not the
  // launcher's.
  void expectNothingLeft(ShmJanitor* since = nullptr) {
    EXPECT_TRUE(processesOnDomain(domain_).empty()) << "processes left on domain " << domain_;
    std::string left;
    for (const std::string& f : ofDomain((since ? *since : janitor_).zombies(), domain_)) left += " " + f;
    EXPECT_TRUE(left.empty()) << "the launcher left shared-memory files behind:" << left;
  }

  OwnShm own_shm_;      // first: this test's /dev/shm is its own (private_shm.h)
  ShmJanitor janitor_;  // outlives every process the test starts
  std::string swarm_;
  fs::path dir_;
  int domain_ = testDomain(31);
};

TEST_F(LaunchTest, MalformedScenarioStartsNothing) {
  // GIVEN a scenario file with two invalid values
  const fs::path bad = dir_ / "bad.yaml";
  std::ofstream(bad) << "uav_count: -3\nagent:\n  k: many\n";
  // WHEN the launcher is given it
  Child c({kLaunch, "--scenario", bad.string(), "--out", (dir_ / "out").string(), "--domain", std::to_string(domain_)},
          dir_ / "launch.log");
  // THEN it exits 2, naming every problem, and starts or writes nothing
  EXPECT_EQ(c.wait(30.0), 2);
  const std::string log = readFile(dir_ / "launch.log");
  EXPECT_NE(log.find("invalid scenario"), std::string::npos) << log;
  EXPECT_NE(log.find("uav_count"), std::string::npos) << log;  // every problem named, not just the first
  EXPECT_NE(log.find("k"), std::string::npos) << log;
  EXPECT_FALSE(fs::exists(dir_ / "out")) << "nothing may be started or written";

  // WHEN it is given an unknown option and an override that is no number THEN it exits 2, naming the option
  Child unknown({kLaunch, "--scenario", kScenario, "--bogus", "--set", "duration_s=abc"}, dir_ / "launch2.log");
  EXPECT_EQ(unknown.wait(30.0), 2);
  const std::string log2 = readFile(dir_ / "launch2.log");
  EXPECT_NE(log2.find("--bogus"), std::string::npos) << log2;
  // AND nothing of either launch is left
  expectNothingLeft();
}

TEST_F(LaunchTest, FourAgentsSixtySecondsStayCohesive) {
  // WHEN the launcher runs the 4-UAV GNSS-loss scenario for 60 s (lockstep)
  Child launch(launchArgs({"--set", "duration_s=60"}), dir_ / "launch.log");
  // THEN it exits with the monitor's PASS
  const auto status = launch.wait(180.0);
  const std::string log = readFile(dir_ / "launch.log");
  ASSERT_TRUE(status.has_value()) << log;
  EXPECT_EQ(*status, 0) << log;  // PASS verdict

  // AND the monitor's summary shows a cohesive swarm: d_NB within 10 % of r, no collision, no restart
  const fs::path out = dir_ / "out";
  const std::string summary = readFile(out / "summary.json");
  ASSERT_FALSE(summary.empty()) << log;
  const double d_nb = jsonNumber(summary, "mean_neighbor_distance_m");
  EXPECT_NEAR(d_nb, 10.0, 1.0) << "d_NB within ±10 % of r = 10 m";
  EXPECT_EQ(jsonNumber(summary, "collisions"), 0.0);
  EXPECT_EQ(jsonNumber(summary, "agent_restarts"), 0.0);

  // AND the DDS processes and the in-process loop (swa_batch's) agree exactly: lockstep delivers every sample in the
  // closed loop's order, and each agent publishes its state once all of a step's samples are processed.
  const batch::RunResult oracle = batch::runClosedLoop(sim::loadScenario(kScenario, {"duration_s=60"}));
  int compared = 0;
  for (const monitor::NamedValue& f : monitor::summaryFields(oracle.summary)) {
    const double dds = jsonNumber(summary, f.key);
    if (std::isnan(f.value)) {
      EXPECT_TRUE(std::isnan(dds)) << f.key;
    } else {
      EXPECT_EQ(dds, f.value) << f.key;
    }
    ++compared;
  }
  EXPECT_GE(compared, 20);
  // AND the run directory holds the report, the time series, the effective scenario, the logs and the restart log
  for (const char* f : {"report.html", "timeseries.csv", "scenario.yaml", "logs/sim.log", "logs/monitor.log",
                        "logs/agent_0.log", "logs/agent_3.log", "logs/restarts.csv"}) {
    EXPECT_TRUE(fs::exists(out / f)) << f;
  }
  // AND nothing is left: no process on the domain, no shared-memory file
  expectNothingLeft();
}

// Issue #12: the user's files are read once, by the launcher; every child reads the run's effective scenario.yaml and
// no --set, so an `agent.k` lives in one file and the run directory holds exactly the configuration that ran.
TEST_F(LaunchTest, EveryChildReadsTheRunsEffectiveConfigurationAndNoSet) {
  // GIVEN a realtime launch with overrides of the scenario and of the agents
  Child launch(launchArgs({"--set", "clock.mode=realtime", "--set", "duration_s=60", "--set", "agent.k=2", "--set",
                           "agent.formation.neighbourhood=k_nearest"}),
               dir_ / "launch.log");
  const fs::path out = dir_ / "out";
  const fs::path effective = out / "scenario.yaml";
  const auto deadline = SteadyClock::now() + std::chrono::seconds(60);
  while (SteadyClock::now() < deadline && readFile(out / "logs" / "sim.log").find("discovered") == std::string::npos &&
         !launch.wait(0.0)) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  // WHEN the swarm runs THEN the run directory holds the effective scenario, overrides applied
  const sim::Scenario expected = sim::loadScenario(
      kScenario, {"clock.mode=realtime", "duration_s=60", "agent.k=2", "agent.formation.neighbourhood=k_nearest"});
  EXPECT_EQ(sim::scenarioToYaml(sim::loadScenario(effective.string())), sim::scenarioToYaml(expected));
  EXPECT_EQ(sim::loadScenario(effective.string()).agent.formation.k, 2);
  // AND beside it the agents' configuration as that scenario implies it (issue #47: an agent reads no scenario)
  const fs::path agents = out / "agent.yaml";
  EXPECT_EQ(agent::toYaml(agent::loadAgentConfig(agents.string())), agent::toYaml(expected.agent));
  // AND every child on the domain (simulator, 4 agents, monitor) was given its file and no --set
  int children = 0;
  for (int pid : processesOnDomain(domain_)) {
    std::string cmdline = readFile(fs::path("/proc") / std::to_string(pid) / "cmdline");
    std::replace(cmdline.begin(), cmdline.end(), '\0', ' ');
    const std::string program = cmdline.substr(0, cmdline.find(' '));
    if (program.size() >= 10 && program.compare(program.size() - 10, 10, "swa_launch") == 0) continue;
    ++children;
    const bool agent = cmdline.find("swa_agent ") != std::string::npos;
    const std::string given = agent ? "--config " + agents.string() : "--scenario " + effective.string();
    EXPECT_NE(cmdline.find(given), std::string::npos) << cmdline;
    EXPECT_EQ(cmdline.find("--set"), std::string::npos) << cmdline;
  }
  EXPECT_EQ(children, 6);
  launch.signal(SIGTERM);
  EXPECT_TRUE(launch.wait(60.0).has_value());
  expectNothingLeft();
}

// Agent 2 is SIGKILLed mid-run. The launcher must restart it; the new process must rebuild its picture of the
// swarm (it ends tracking its neighbours), and the run must stay cohesive.
TEST_F(LaunchTest, KilledAgentIsRestartedAndRejoins) {
  // GIVEN a lockstep launch of 240 s, and an observer of agent 2's state in this test
  constexpr int kVictim = 2;
  auto watch = std::make_unique<StateStampWatch>(domain_, kVictim);
  // Long enough in simulated time that the swarm runs well after the restart (lockstep runs ~20x real time).
  ShmJanitor launcher_files;
  Child launch(launchArgs({"--set", "duration_s=240"}), dir_ / "launch.log");
  // WHEN agent 2 is SIGKILLed once the run is past 20 s
  ASSERT_GT(watch->killWhenReached(20'000'000'000LL, launch, [&] { return agentPid(domain_, kVictim); }), 0)
      << readFile(dir_ / "launch.log");
  // THEN the launcher exits with PASS
  const auto status = launch.wait(180.0);
  const std::string log = readFile(dir_ / "launch.log");
  ASSERT_TRUE(status.has_value()) << log;
  EXPECT_EQ(*status, 0) << log;
  // AND this test's participant, which had been receiving from the killed process, heard the new one. (It did not in
  // about 1 run in 6 while the new process took over the killed one's shared-memory port: swa/dds/participant_id.h.)
  EXPECT_EQ(watch->newProcessesHeard(), 1) << readFile(dir_ / "out" / "logs" / "agent_2.log");
  watch.reset();
  // AND the restarted process tracked its neighbours again: its own final line, after the launcher's restart marker
  const std::string agent_log = readFile(dir_ / "out" / "logs" / "agent_2.log");
  const std::size_t marker = agent_log.find("==== swa_launch: restart 1");
  ASSERT_NE(marker, std::string::npos) << agent_log;
  EXPECT_TRUE(std::regex_search(agent_log.substr(marker),
                                std::regex("final stage tracking, [0-9]+ confirmed track\\(s\\), frame fitted on [2-9] "
                                           "neighbour")))
      << agent_log;
  // AND the restart is in the restart log, the summary and the report, the run stayed cohesive, and the launcher
  // logged the agent's end
  const fs::path out = dir_ / "out";
  const std::string restarts = readFile(out / "logs" / "restarts.csv");
  EXPECT_TRUE(std::regex_search(restarts, std::regex("\n[0-9.]+,2,137,1,"))) << restarts;  // uav 2, SIGKILL
  const std::string summary = readFile(out / "summary.json");
  EXPECT_EQ(jsonNumber(summary, "agent_restarts"), 1.0) << summary;
  EXPECT_EQ(jsonNumber(summary, "collisions"), 0.0);
  EXPECT_NEAR(jsonNumber(summary, "mean_neighbor_distance_m"), 10.0, 1.0);
  EXPECT_NE(readFile(out / "report.html").find("restart"), std::string::npos) << "the restart is not in the report";
  EXPECT_NE(log.find("agent 2 ended (signal 9"), std::string::npos) << log;
  // AND nothing of the run is left
  expectNothingLeft(&launcher_files);
}

// Issue #11: kill -9 of the monitor under swa_launch ended the whole run with no summary and printed the path of a
// report that did not exist. Now the monitor is restarted like an agent, and the new one says what it missed.
TEST_F(LaunchTest, KilledMonitorIsRestartedAndSaysWhatItMissed) {
  // GIVEN a lockstep launch of 400 s, and an observer of agent 0's state in this test
  auto watch = std::make_unique<StateStampWatch>(domain_, 0);
  ShmJanitor launcher_files;
  Child launch(launchArgs({"--set", "duration_s=400"}), dir_ / "launch.log");
  // WHEN the monitor is SIGKILLed once the run is past 200 s (the simulator's truth history reaches 100 s back, so
  // the restarted monitor cannot get the first 100 s; the chaos test kills it early enough to recover everything)
  ASSERT_GT(watch->killWhenReached(200'000'000'000LL, launch, [&] { return monitorPid(domain_); }), 0)
      << readFile(dir_ / "launch.log");
  watch.reset();
  const auto status = launch.wait(180.0);
  const std::string log = readFile(dir_ / "launch.log");
  ASSERT_TRUE(status.has_value()) << log;
  // THEN the launcher restarted it, the run ran to its end, and the report it names exists
  EXPECT_NE(log.find("swa_monitor ended (signal 9"), std::string::npos) << log;
  const fs::path out = dir_ / "out";
  EXPECT_TRUE(fs::exists(out / "report.html")) << log;
  EXPECT_NE(readFile(out / "logs" / "monitor.log").find("==== swa_launch: restart 1"), std::string::npos);
  // AND its verdict is INCOMPLETE (exit 3), naming the part of the run it missed, not a PASS on what it saw
  EXPECT_EQ(*status, 3) << log;
  const std::string summary = readFile(out / "summary.json");
  EXPECT_NE(summary.find("\"verdict\": \"INCOMPLETE\""), std::string::npos) << summary;
  EXPECT_NE(summary.find("the monitor missed"), std::string::npos) << summary;
  EXPECT_GE(jsonNumber(summary, "truth_missed_ms"), 50'000.0) << summary;
  // AND the restart is in the restart log and the summary, apart from the agents'
  EXPECT_TRUE(std::regex_search(readFile(out / "logs" / "restarts.csv"), std::regex("\n[0-9.]+,monitor,137,1,")))
      << readFile(out / "logs" / "restarts.csv");
  EXPECT_EQ(jsonNumber(summary, "monitor_restarts"), 1.0) << summary;
  EXPECT_EQ(jsonNumber(summary, "agent_restarts"), 0.0) << summary;
  // AND nothing of the run is left
  expectNothingLeft(&launcher_files);
}

// A monitor that no longer hears its own shared-memory port (a peer re-created it under it) would record nothing more
// while the run goes on: it says so, re-creates its participant, and reads the rest of the run (issue #46;
// swa/dds/deaf_port_watch.h). The state is made directly, as in test_dds_swarm.cpp: its port files deleted and
// created again under it.
TEST_F(LaunchTest, MonitorDeafOnItsOwnSharedMemoryPortReCreatesItsParticipantAndMissesNothing) {
  // GIVEN a recorded lockstep launch of 200 s, and an observer of agent 0's state in this test
  auto watch = std::make_unique<StateStampWatch>(domain_, 0);
  ShmJanitor launcher_files;
  Child launch(launchArgs({"--set", "duration_s=200", "--record"}), dir_ / "launch.log");
  const fs::path monitor_log = dir_ / "out" / "logs" / "monitor.log";
  // WHEN the monitor's port files are re-created under it once the run is past 50 s
  ASSERT_TRUE(watch->waitUntil(50'000'000'000LL, launch)) << readFile(dir_ / "launch.log");
  watch.reset();
  const int monitor = monitorPid(domain_);
  ASSERT_GT(monitor, 0);
  const std::set<int> ports = listedPorts(readFile(monitor_log), "swa_monitor");
  ASSERT_GE(ports.size(), 2u) << readFile(monitor_log);  // metatraffic and user data
  for (const int port : ports) EXPECT_TRUE(holdsOpen(monitor, lockFileOf(port))) << port;
  const std::vector<fs::path> made = recreatePortFiles(ports);
  const auto status = launch.wait(180.0);
  removeFiles(made);
  const std::string log = readFile(dir_ / "launch.log");
  ASSERT_TRUE(status.has_value()) << log;
  // THEN it named one of them and re-created its participant, in the same process (no restart)
  const std::string monitor_said = readFile(monitor_log);
  EXPECT_EQ(ports.count(deafPortNamed(monitor_said)), 1u) << monitor_said;
  EXPECT_NE(monitor_said.find("swa_monitor: deaf on shared-memory port"), std::string::npos) << monitor_said;
  EXPECT_EQ(monitor_said.find("==== swa_launch: restart"), std::string::npos) << monitor_said;
  // AND the run passed with nothing missed: the new readers got what the old ones missed from the writers' history
  EXPECT_EQ(*status, 0) << log << monitor_said;
  const std::string summary = readFile(dir_ / "out" / "summary.json");
  EXPECT_NE(summary.find("\"verdict\": \"PASS\""), std::string::npos) << summary;
  EXPECT_EQ(jsonNumber(summary, "truth_missed_ms"), 0.0) << summary;
  EXPECT_EQ(jsonNumber(summary, "monitor_restarts"), 0.0) << summary;
  // AND the recording holds no sample twice: the new readers were sent their writers' history again, and what the old
  // ones had recorded was not recorded again (recording.json counts those repeats: at least the agents' states, whose
  // writers keep 100 s). What reached only the deaf port and its writer no longer keeps (commands, KEEP_LAST 1) is
  // not in it: the recording has a gap there, as long as the simulator ran on without the monitor.
  const replay::RecordedRun recorded =
      replay::readRecordedRun((dir_ / "out" / "run.mcap").string(), std::nullopt, false);
  ASSERT_EQ(recorded.uavs.size(), 4u);
  const auto stampOf = [](const replay::Payload& p) {
    const auto stamp = recording::payloadStamp(p.data(), p.size());
    return stamp ? static_cast<std::int64_t>(stamp->stamp_ns) : -1;
  };
  for (const auto& [uav, r] : recorded.uavs) {
    std::set<std::int64_t> commands;
    for (const replay::Payload& p : r.commands) commands.insert(stampOf(p));
    EXPECT_EQ(commands.size(), r.commands.size()) << "UAV " << uav << ": a command recorded twice";
    std::set<std::pair<int, std::int64_t>> inputs;
    for (const replay::InputSample& in : r.inputs) inputs.insert({static_cast<int>(in.input), stampOf(in.payload)});
    EXPECT_EQ(inputs.size(), r.inputs.size()) << "UAV " << uav << ": a sensor sample recorded twice";
  }
  EXPECT_GT(jsonNumber(readFile(dir_ / "out" / "recording.json"), "repeats"), 0.0);
  expectNothingLeft(&launcher_files);
}

// A recording monitor that stalls in realtime (a loaded host: CI did it) must lose no command: nothing holds the
// swarm for it, and an agent's command writer keeps only its newest setpoint (KEEP_LAST 1), so what its transport
// drops is never repaired. Its shared-memory port queues what arrives meanwhile (profiles.xml, swa_shm): with Fast
// DDS's default queue a 1 s stop lost about half a second of every UAV's commands (issue #46).
TEST_F(LaunchTest, ARecordingMonitorStoppedForASecondInRealtimeLosesNoCommand) {
  // GIVEN a realtime launch of 4 UAVs, recorded, and an observer of agent 0's state in this test
  auto watch = std::make_unique<StateStampWatch>(domain_, 0);
  Child launch(launchArgs({"--set", "clock.mode=realtime", "--set", "duration_s=8", "--record"}), dir_ / "launch.log");
  // WHEN the monitor is stopped for 1 s once the swarm is 3 s in
  ASSERT_TRUE(watch->waitUntil(3'000'000'000LL, launch)) << readFile(dir_ / "launch.log");
  watch.reset();
  const int monitor = monitorPid(domain_);
  ASSERT_GT(monitor, 0);
  ASSERT_EQ(::kill(monitor, SIGSTOP), 0);
  std::this_thread::sleep_for(std::chrono::seconds(1));
  ASSERT_EQ(::kill(monitor, SIGCONT), 0);
  const auto status = launch.wait(120.0);
  const std::string log = readFile(dir_ / "launch.log");
  ASSERT_TRUE(status.has_value()) << log;
  EXPECT_EQ(*status, 0) << log;
  // THEN the recording holds every command the agents sent: re-run in-process on it (swa_replay --check), each UAV's
  // commands all come out again and each has its recorded twin, byte for byte
  const fs::path recording = dir_ / "out" / "run.mcap";
  const replay::RecordedRun recorded = replay::readRecordedRun(recording.string(), std::nullopt, false);
  ASSERT_TRUE(recorded.scenario_yaml);
  const std::vector<replay::UavCheck> checks =
      replay::checkRun(recorded, sim::parseRecordedScenario(*recorded.scenario_yaml, "run.mcap", {}).agent);
  ASSERT_EQ(checks.size(), 4u) << replay::formatChecks(checks);
  for (const replay::UavCheck& c : checks) {
    EXPECT_GE(c.replayed, 700u) << replay::formatChecks(checks);  // 8 s at 100 Hz
    EXPECT_EQ(c.not_recorded, 0u) << replay::formatChecks(checks);
    EXPECT_TRUE(c.identicalRun()) << replay::formatChecks(checks);
  }
  expectNothingLeft();
}

// Issue #11: a stray scenario-end event on the domain ended a 40 s run at 18 s as "PASS, completed", and two runs on
// one domain mixed silently. Each launch is a swarm of its own (a DDS partition): two of them side by side on one
// domain, and a stray publisher there, change nothing.
TEST_F(LaunchTest, TwoSwarmsAndAStrayEndEventOnOneDomainDoNotMix) {
  // GIVEN two launches of the same scenario at once on this test's domain, each its own swarm (20 s each)
  ::unsetenv("SWA_SWARM");
  Child a(launchArgs({"--set", "duration_s=20", "--swarm", swarm_ + "-a"}), dir_ / "a.log");
  std::vector<std::string> b_args = launchArgs({"--set", "duration_s=20", "--swarm", swarm_ + "-b"});
  for (std::string& arg : b_args) {
    if (arg == (dir_ / "out").string()) arg = (dir_ / "out_b").string();
  }
  Child b(b_args, dir_ / "b.log");
  // AND a stray publisher on the same domain (default partition) announcing the end of "the" scenario every 50 ms
  auto stray = std::make_unique<dds::Participant>("swa_test_stray", domain_, dds::resolveProfilesFile());
  auto events = stray->writer<msg::ScenarioEventPubSubType>(dds::topics::kEvents, dds::qos::kEventWriter);
  msg::ScenarioEvent end;
  end.kind(msg::EVENT_SCENARIO_END);
  end.text("completed");
  const auto deadline = SteadyClock::now() + std::chrono::seconds(120);
  // WHEN both run to their end, the stray publisher writing all the while
  while ((!a.wait(0.0) || !b.wait(0.0)) && SteadyClock::now() < deadline) {
    events.write(end);
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  stray.reset();
  // THEN both complete their 20 s with PASS, and each is exactly the in-process loop: nothing crossed over
  ASSERT_EQ(a.wait(120.0), std::optional<int>(0)) << readFile(dir_ / "a.log");
  ASSERT_EQ(b.wait(120.0), std::optional<int>(0)) << readFile(dir_ / "b.log");
  const batch::RunResult oracle = batch::runClosedLoop(sim::loadScenario(kScenario, {"duration_s=20"}));
  for (const fs::path& out : {dir_ / "out", dir_ / "out_b"}) {
    SCOPED_TRACE(out.string());
    const std::string summary = readFile(out / "summary.json");
    EXPECT_NE(summary.find("\"end_reason\": \"completed\""), std::string::npos) << summary;
    EXPECT_EQ(jsonNumber(summary, "duration_s"), oracle.summary.duration_s) << summary;
    EXPECT_EQ(jsonNumber(summary, "mean_neighbor_distance_m"), oracle.summary.mean_neighbor_distance_m);
    EXPECT_EQ(jsonNumber(summary, "anees_position"), oracle.summary.anees_position) << summary;
  }
  // AND the first launch logged its swarm, and nothing of either is left
  EXPECT_NE(readFile(dir_ / "a.log").find("swarm " + swarm_ + "-a"), std::string::npos);
  expectNothingLeft();
}

// SIGTERM to the launcher mid-run: forwarded, the monitor writes what it has (verdict INCOMPLETE = 3), and every
// process and shared-memory file is gone.
TEST_F(LaunchTest, SigtermStopsEverythingCleanly) {
  // GIVEN a realtime launch of 600 s, and an observer of agent 0's state in this test
  auto watch = std::make_unique<StateStampWatch>(domain_, 0);
  Child launch(launchArgs({"--set", "clock.mode=realtime", "--set", "duration_s=600"}), dir_ / "launch.log");
  // WHEN the world has run a little: agent 0 has published its state for 2 s of simulated time, which in realtime is
  // 2 s of the run (a bounded wait, given up if the launcher exits)
  ASSERT_TRUE(watch->waitUntil(2'000'000'000LL, launch)) << "the world never ran\n" << readFile(dir_ / "launch.log");
  watch.reset();
  // AND the launcher gets SIGTERM
  launch.signal(SIGTERM);
  // THEN it exits with the monitor's INCOMPLETE (3), and the monitor wrote a summary of an incomplete run
  const auto status = launch.wait(60.0);
  const std::string log = readFile(dir_ / "launch.log");
  ASSERT_TRUE(status.has_value()) << log;
  EXPECT_EQ(*status, 3) << log;
  const std::string summary = readFile(dir_ / "out" / "summary.json");
  EXPECT_NE(summary.find("\"completed\": false"), std::string::npos) << summary;
  // AND every process and shared-memory file is gone
  expectNothingLeft();
}

// --compare standalone: the same seed twice, both runs in one report, exit status = the SWA run's verdict.
TEST_F(LaunchTest, CompareStandaloneWritesOneReport) {
  // WHEN the launcher runs a 30 s scenario with --compare standalone
  Child launch(launchArgs({"--set", "duration_s=30", "--compare", "standalone"}), dir_ / "launch.log");
  // THEN it exits with the SWA run's PASS
  const auto status = launch.wait(180.0);
  const std::string log = readFile(dir_ / "launch.log");
  ASSERT_TRUE(status.has_value()) << log;
  EXPECT_EQ(*status, 0) << log;
  // AND each run has its own summary, and one report shows both
  const fs::path out = dir_ / "out";
  EXPECT_TRUE(fs::exists(out / "swa" / "summary.json"));
  EXPECT_TRUE(fs::exists(out / "standalone" / "summary.json"));
  const std::string report = readFile(out / "report.html");
  EXPECT_NE(report.find("swa"), std::string::npos);
  EXPECT_NE(report.find("standalone"), std::string::npos);
  // AND the comparison report and each run's name the build that wrote them (issue #30: "Version —")
  for (const fs::path& r : {out / "report.html", out / "swa" / "report.html", out / "standalone" / "report.html"}) {
    EXPECT_NE(readFile(r).find("<dt>Version</dt><dd>" + app::programVersion() + "</dd>"), std::string::npos) << r;
  }
  // AND nothing of either run is left
  expectNothingLeft();
}

// A mission changed live by swa_mission (issue #45): the agents fly it, and the monitor judges the run against it.
TEST_F(LaunchTest, AMissionChangedLiveBySwaMissionIsFlownAndJudgedAgainstTheNewPlan) {
  // GIVEN a realtime launch flying east at 2 m/s from 0 s, for longer than the run
  Child launch(launchArgs({"--set", "duration_s=30", "--set", "clock.mode=realtime", "--set", "mission.start=time",
                           "--set", "mission.legs=[{velocity_mps: [2, 0], duration_s: 60}]"}),
               dir_ / "launch.log");
  // WHEN the ground sends "north at 2 m/s for 8 s" as soon as the 4 agents and the monitor read the topic
  Child ground({SWA_MISSION_BINARY, "--leg", "vel:0,2,8", "--expect", "5", "--wait-s", "60", "--domain",
                std::to_string(domain_)},
               dir_ / "ground.log");
  const auto sent = ground.wait(90.0);
  ASSERT_TRUE(sent.has_value()) << readFile(dir_ / "ground.log");
  EXPECT_EQ(*sent, 0) << readFile(dir_ / "ground.log");
  // THEN the run PASSes, judged against the changed plan: the swarm ends where it ends (against the scenario's plan
  // it would be tens of metres off)
  const auto status = launch.wait(150.0);
  const fs::path out = dir_ / "out";
  const std::string log = readFile(dir_ / "launch.log") + readFile(out / "logs" / "monitor.log");
  ASSERT_TRUE(status.has_value()) << log;
  EXPECT_EQ(*status, 0) << log;
  const std::string summary = readFile(out / "summary.json");
  EXPECT_NE(summary.find("\"verdict\": \"PASS\""), std::string::npos) << summary;
  EXPECT_LT(jsonNumber(summary, "mission_end_error_m"), 3.0) << summary;
  EXPECT_EQ(jsonNumber(summary, "collisions"), 0.0);
  EXPECT_NE(log.find("mission 1 from the ground: the run is scored against it"), std::string::npos) << log;
  expectNothingLeft();
}

// --transport discovery-server without a server address: the launcher starts fast-discovery-server on 127.0.0.1,
// every child is a UDP-only client of it, and the server is stopped with the run. The run is the same experiment:
// lockstep gives the in-process loop's d_NB exactly over this transport too.
TEST_F(LaunchTest, DiscoveryServerTransportStaysCohesiveAndStopsTheServer) {
  // GIVEN a port of this test's own for a discovery server
  const std::string port = std::to_string(20000 + domain_);  // distinct per domain, as concurrent launches need
  // WHEN the launcher runs a 30 s scenario over the discovery-server transport without a server address
  Child launch(launchArgs({"--set", "duration_s=30", "--transport", "discovery-server", "--discovery-port", port}),
               dir_ / "launch.log");
  // THEN it exits with PASS
  const auto status = launch.wait(180.0);
  const std::string log = readFile(dir_ / "launch.log");
  ASSERT_TRUE(status.has_value()) << log;
  EXPECT_EQ(*status, 0) << log;
  // AND it started a discovery server on 127.0.0.1 at that port and shut it down cleanly
  const fs::path out = dir_ / "out";
  const std::string server_log = readFile(out / "discovery_server.log");
  EXPECT_NE(server_log.find("UDPv4:[127.0.0.1]:" + port), std::string::npos) << server_log;
  EXPECT_NE(server_log.find("Server shut down"), std::string::npos) << "stopped cleanly: " << server_log;
  // AND the run is the in-process loop's, d_NB within 10 % of r, with no collision
  const std::string summary = readFile(out / "summary.json");
  const batch::RunResult oracle = batch::runClosedLoop(sim::loadScenario(kScenario, {"duration_s=30"}));
  EXPECT_EQ(jsonNumber(summary, "mean_neighbor_distance_m"), oracle.summary.mean_neighbor_distance_m) << log;
  EXPECT_NEAR(jsonNumber(summary, "mean_neighbor_distance_m"), 10.0, 1.0);
  EXPECT_EQ(jsonNumber(summary, "collisions"), 0.0);
  // AND no discovery server is left running, nor anything else of the run
  for (const auto& e : fs::directory_iterator("/proc")) {
    const std::string cmdline = readFile(e.path() / "cmdline");
    EXPECT_FALSE(cmdline.find("fast-discovery-server") != std::string::npos && cmdline.find(port) != std::string::npos)
        << "discovery server still running: pid " << e.path().filename();
  }
  expectNothingLeft();
}

TEST_F(LaunchTest, UnwritableOutputStartsNothingAndExits2) {
  // GIVEN an output directory that cannot be created (issue #11: this ran the monitor and exited 3)
  Child c({kLaunch, "--scenario", kScenario, "--out", "/proc/swa_nope", "--domain", std::to_string(domain_)},
          dir_ / "launch.log");
  // THEN it is a usage error, named, and nothing starts
  EXPECT_EQ(c.wait(30.0), 2);
  EXPECT_NE(readFile(dir_ / "launch.log").find("cannot create --out /proc/swa_nope"), std::string::npos)
      << readFile(dir_ / "launch.log");
  expectNothingLeft();
}

TEST_F(LaunchTest, BadDeploymentStartsNothing) {
  // WHEN the launcher is given a transport typo THEN it exits 2 before anything starts, naming the transports
  Child typo(launchArgs({"--transport", "shm"}), dir_ / "typo.log");
  EXPECT_EQ(typo.wait(30.0), 2);
  EXPECT_NE(readFile(dir_ / "typo.log").find("--transport must be local, network or discovery-server"),
            std::string::npos)
      << readFile(dir_ / "typo.log");
  // WHEN it is given credentials that do not exist THEN it exits 2, naming every missing file and the script that
  // makes them
  Child insecure(launchArgs({"--secure", (dir_ / "no_such_creds").string()}), dir_ / "secure.log");
  EXPECT_EQ(insecure.wait(30.0), 2);
  const std::string log = readFile(dir_ / "secure.log");
  EXPECT_NE(log.find("missing credentials"), std::string::npos) << log;
  EXPECT_NE(log.find("swa_agent_3/permissions.p7s"), std::string::npos) << "every missing file named: " << log;
  EXPECT_NE(log.find("make-credentials.sh"), std::string::npos) << log;
  // AND nothing was written, and nothing is left
  EXPECT_FALSE(fs::exists(dir_ / "out")) << "nothing may be started or written";
  expectNothingLeft();
}

}  // namespace
}  // namespace swa::testing

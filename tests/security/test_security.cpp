// DDS Security end to end (issue #5), with credentials made by deploy/security/make-credentials.sh in a temporary
// directory per test (removed afterwards, also on failure): a secure swarm stays cohesive; each role can create
// exactly the endpoints its permissions grant (UAV 2's credentials cannot read UAV 1's detections nor command
// UAV 1); a participant without credentials matches nothing of a secure swarm; tampered or foreign permissions are
// refused at start with a message naming the file and the cause. Every check that something is refused has a
// positive control in the same setup, so no case can pass just because nothing worked. Processes run on a private
// domain and are reaped, and shared-memory files of killed processes removed, also when a check fails.

#include <signal.h>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include <swa/msg/AgentStatePubSubTypes.h>
#include <swa/msg/BridgeStatePubSubTypes.h>
#include <swa/msg/ClockPubSubTypes.h>
#include <swa/msg/DetectionsPubSubTypes.h>
#include <swa/msg/GnssFixPubSubTypes.h>
#include <swa/msg/ImuPubSubTypes.h>
#include <swa/msg/ScenarioEventPubSubTypes.h>
#include <swa/msg/SensorFramePubSubTypes.h>
#include <swa/msg/SwarmTruthPubSubTypes.h>
#include <swa/msg/VelocitySetpointPubSubTypes.h>
#include <swa/px4/OffboardControlMode_v1_15PubSubTypes.h>
#include <swa/px4/SensorCombined_v1_15PubSubTypes.h>
#include <swa/px4/TrajectorySetpoint_v1_15PubSubTypes.h>
#include <swa/px4/VehicleAttitude_v1_15PubSubTypes.h>
#include <swa/px4/VehicleOdometry_v1_15PubSubTypes.h>
#include <swa/px4/VehicleStatus_v1_15PubSubTypes.h>
#include <swa/px4/VehicleStatus_v1_16PubSubTypes.h>
#include <swa/ros/ArdupilotServicesPubSubTypes.h>
#include <swa/ros/ArdupilotStatusPubSubTypes.h>
#include <swa/ros/ImuPubSubTypes.h>
#include <swa/ros/TFMessagePubSubTypes.h>
#include <swa/ros/TwistStampedPubSubTypes.h>

#include "../integration/process_test.h"
#include "../integration/resting_imu.h"
#include "swa/dds/handshake_watch.h"
#include "swa/dds/options.h"
#include "swa/dds/participant.h"
#include "swa/dds/qos_profiles.h"
#include "swa/dds/topics.h"

namespace swa::testing {
namespace {

const std::string kSourceDir = SWA_SOURCE_DIR;
const std::string kMakeCredentials = kSourceDir + "/deploy/security/make-credentials.sh";
const std::string kScenario = kSourceDir + "/deploy/scenarios/dropout_4.yaml";
const std::string kLaunch = SWA_LAUNCH_BINARY;
const std::string kSim = SWA_SIM_BINARY;
const std::string kAgent = SWA_AGENT_BINARY;
constexpr int kUavs = 4;  // dropout_4.yaml
// Participant::Participant's message when Fast DDS refuses the credentials (idl/runtime/dds/src/participant.cpp).
const std::string kRefused = "DDS Security refused the credentials of participant 'swa_agent_1'";

double secondsSince(SteadyClock::time_point t0) {
  return std::chrono::duration<double>(SteadyClock::now() - t0).count();
}

// Every file of a directory (a run's logs/), for failure messages.
std::string allLogs(const fs::path& dir) {
  std::string s;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec)) s += "--- " + e.path().string() + "\n" + readFile(e.path());
  return s;
}

// SWA_SECURITY_DIR for participants created in this process while it lives (Participant reads it at
// construction). Set only between constructions, from the test thread.
class SecurityDirScope {
 public:
  explicit SecurityDirScope(const std::optional<fs::path>& dir) {
    if (const char* old = std::getenv("SWA_SECURITY_DIR")) old_ = old;
    if (dir) {
      ::setenv("SWA_SECURITY_DIR", dir->c_str(), 1);
    } else {
      ::unsetenv("SWA_SECURITY_DIR");
    }
  }
  ~SecurityDirScope() {
    if (old_) {
      ::setenv("SWA_SECURITY_DIR", old_->c_str(), 1);
    } else {
      ::unsetenv("SWA_SECURITY_DIR");
    }
  }
  SecurityDirScope(const SecurityDirScope&) = delete;
  SecurityDirScope& operator=(const SecurityDirScope&) = delete;

 private:
  std::optional<std::string> old_;
};

std::unique_ptr<dds::Participant> makeParticipant(const std::string& name, int domain,
                                                  const std::optional<fs::path>& security_dir) {
  SecurityDirScope scope(security_dir);
  return std::make_unique<dds::Participant>(name, domain, dds::resolveProfilesFile());
}

enum class Kind { kReader, kWriter };

const char* kindName(Kind k) { return k == Kind::kReader ? "reader" : "writer"; }

template <class PubSub>
void createWith(dds::Participant& p, Kind kind, const std::string& topic, const char* writer_profile,
                const char* reader_profile) {
  if (kind == Kind::kWriter) {
    p.writer<PubSub>(topic, writer_profile);
  } else {
    p.reader<PubSub>(topic, reader_profile, [](typename PubSub::type&&) {});
  }
}

bool endsWith(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// One endpoint on `topic` with the message type and QoS profile the SWA nodes use for it. Throws DdsError when the
// middleware refuses it.
void createEndpoint(dds::Participant& p, Kind kind, const std::string& topic) {
  // ArduPilot's topics and services (the bridge's and the simulator's ArduPilot stand-in's), with AP_DDS's QoS.
  if (topic.rfind("rt/ap/", 0) == 0 || topic.rfind("rq/ap/", 0) == 0 || topic.rfind("rr/ap/", 0) == 0) {
    namespace srv = ardupilot_msgs::srv;
    if (endsWith(topic, "/imu/experimental/data")) {
      return createWith<sensor_msgs::msg::ImuPubSubType>(p, kind, topic, dds::qos::kApOutWriter,
                                                         dds::qos::kApOutReader);
    }
    if (endsWith(topic, "/status")) {
      return createWith<ardupilot_msgs::msg::StatusPubSubType>(p, kind, topic, dds::qos::kApStatusWriter,
                                                               dds::qos::kApStatusReader);
    }
    if (endsWith(topic, "/cmd_vel")) {
      return createWith<geometry_msgs::msg::TwistStampedPubSubType>(p, kind, topic, dds::qos::kApInWriter,
                                                                    dds::qos::kApInReader);
    }
    if (endsWith(topic, "/tf")) {
      return createWith<tf2_msgs::msg::TFMessagePubSubType>(p, kind, topic, dds::qos::kApInWriter,
                                                            dds::qos::kApInReader);
    }
    if (endsWith(topic, "/arm_motorsRequest")) {
      return createWith<srv::ArmMotors_RequestPubSubType>(p, kind, topic, dds::qos::kApServiceWriter,
                                                          dds::qos::kApServiceReader);
    }
    if (endsWith(topic, "/arm_motorsReply")) {
      return createWith<srv::ArmMotors_ResponsePubSubType>(p, kind, topic, dds::qos::kApServiceWriter,
                                                           dds::qos::kApServiceReader);
    }
    if (endsWith(topic, "/mode_switchRequest")) {
      return createWith<srv::ModeSwitch_RequestPubSubType>(p, kind, topic, dds::qos::kApServiceWriter,
                                                           dds::qos::kApServiceReader);
    }
    if (endsWith(topic, "/mode_switchReply")) {
      return createWith<srv::ModeSwitch_ResponsePubSubType>(p, kind, topic, dds::qos::kApServiceWriter,
                                                            dds::qos::kApServiceReader);
    }
    throw std::logic_error("test bug: no type for topic " + topic);
  }
  if (endsWith(topic, "/imu")) {
    return createWith<msg::ImuPubSubType>(p, kind, topic, dds::qos::kSensorWriter, dds::qos::kSensorReader);
  }
  if (endsWith(topic, "/detections")) {
    return createWith<msg::DetectionsPubSubType>(p, kind, topic, dds::qos::kDetectionsGnssWriter,
                                                 dds::qos::kSensorReader);
  }
  if (endsWith(topic, "/gnss")) {
    return createWith<msg::GnssFixPubSubType>(p, kind, topic, dds::qos::kDetectionsGnssWriter, dds::qos::kSensorReader);
  }
  if (endsWith(topic, "/sensors")) {
    return createWith<msg::SensorFramePubSubType>(p, kind, topic, dds::qos::kFrameWriter, dds::qos::kFrameReader);
  }
  if (endsWith(topic, "/cmd_vel")) {
    return createWith<msg::VelocitySetpointPubSubType>(p, kind, topic, dds::qos::kCommandWriter,
                                                       dds::qos::kCommandReader);
  }
  if (endsWith(topic, "/state")) {
    return createWith<msg::AgentStatePubSubType>(p, kind, topic, dds::qos::kStateWriter, dds::qos::kStateReader);
  }
  if (topic == dds::topics::kTruth) {
    return createWith<msg::SwarmTruthPubSubType>(p, kind, topic, dds::qos::kTruthWriter, dds::qos::kTruthReader);
  }
  if (topic == dds::topics::kEvents) {
    return createWith<msg::ScenarioEventPubSubType>(p, kind, topic, dds::qos::kEventWriter, dds::qos::kEventReader);
  }
  if (topic == dds::topics::kClock) {
    return createWith<msg::ClockPubSubType>(p, kind, topic, dds::qos::kClockWriter, dds::qos::kClockReader);
  }
  if (endsWith(topic, "/bridge_state")) {
    return createWith<msg::BridgeStatePubSubType>(p, kind, topic, dds::qos::kStateWriter, dds::qos::kStateReader);
  }
  // PX4's topics (the bridge's and the simulator's PX4 stand-in's), with PX4's QoS.
  const bool out = topic.find("/fmu/out/") != std::string::npos;
  const char* writer = out ? dds::qos::kPx4OutWriter : dds::qos::kPx4InWriter;
  const char* reader = out ? dds::qos::kPx4OutReader : dds::qos::kPx4InReader;
  if (endsWith(topic, "/vehicle_attitude")) {
    return createWith<px4_msgs::msg::VehicleAttitudePubSubType>(p, kind, topic, writer, reader);
  }
  if (endsWith(topic, "/sensor_combined")) {
    return createWith<px4_msgs::msg::SensorCombinedPubSubType>(p, kind, topic, writer, reader);
  }
  if (endsWith(topic, "/vehicle_status")) {
    return createWith<px4_msgs::msg::VehicleStatusPubSubType>(p, kind, topic, writer, reader);
  }
  if (endsWith(topic, "/vehicle_status_v1")) {
    return createWith<px4_v1_16::px4_msgs::msg::VehicleStatusPubSubType>(p, kind, topic, writer, reader);
  }
  if (endsWith(topic, "/trajectory_setpoint")) {
    return createWith<px4_msgs::msg::TrajectorySetpointPubSubType>(p, kind, topic, writer, reader);
  }
  if (endsWith(topic, "/vehicle_visual_odometry")) {
    return createWith<px4_msgs::msg::VehicleOdometryPubSubType>(p, kind, topic, writer, reader);
  }
  if (endsWith(topic, "/offboard_control_mode")) {
    return createWith<px4_msgs::msg::OffboardControlModePubSubType>(p, kind, topic, writer, reader);
  }
  throw std::logic_error("test bug: no type for topic " + topic);
}

// "" if the endpoint was created, else the DdsError's text.
std::string tryCreate(dds::Participant& p, Kind kind, const std::string& topic) {
  try {
    createEndpoint(p, kind, topic);
    return "";
  } catch (const dds::DdsError& e) {
    return e.what();
  }
}

class SecurityTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = freshTestDir("swa_security_test", /*per_test=*/true);
    creds_ = dir_ / "creds";
    ASSERT_TRUE(makeCredentials(creds_));
  }

  void TearDown() override {
    for (int pid : processesOnDomain(domain_)) ::kill(pid, SIGKILL);  // only after a failed check
    // Private keys never outlive the test; the logs do when a check failed.
    for (const fs::path& c : made_) fs::remove_all(c);
    if (!HasFailure()) fs::remove_all(dir_);
  }

  // deploy/security/make-credentials.sh --bridges DIR 4, timed.
  bool makeCredentials(const fs::path& dir) {
    made_.push_back(dir);
    const auto t0 = SteadyClock::now();
    const fs::path log = dir_ / ("make-credentials." + dir.filename().string() + ".log");
    Child script({"/bin/bash", kMakeCredentials, "--bridges", dir.string(), std::to_string(kUavs)}, log);
    const auto status = script.wait(60.0);
    std::cout << "make-credentials.sh " << dir.filename().string() << " " << kUavs << ": " << secondsSince(t0)
              << " s\n";
    EXPECT_EQ(status, std::optional<int>(0)) << readFile(log);
    return status == std::optional<int>(0);
  }

  std::string securityEnv() const { return "SWA_SECURITY_DIR=" + creds_.string(); }

  // swa_agent --id `id` with this test's credentials.
  std::unique_ptr<Child> startAgent(int id, const std::string& log_name) {
    return std::make_unique<Child>(agentCommand(kAgent, id, domain_), dir_ / log_name,
                                   std::vector<std::string>{securityEnv()});
  }

  // (a') and (a''): a secure launch of `uavs` UAVs through an autopilot's bridges (make-credentials.sh --bridges gave
  // each its own credentials), 30 s of dropout_4.yaml; cohesive, and every vehicle's event `engaged(i)` in events.csv
  // (the bridge's request crossed the secured domain and was answered).
  void secureLaunchThroughAutopilot(const std::string& vehicle, int uavs,
                                    const std::function<std::string(int)>& engaged) {
    const fs::path out = dir_ / "out";
    const auto t0 = SteadyClock::now();
    Child launch({kLaunch, "--secure", creds_.string(), "--vehicle", vehicle, "--scenario", kScenario, "--set",
                  "uav_count=" + std::to_string(uavs), "--set", "duration_s=30", "--domain", std::to_string(domain_),
                  "--out", out.string(), "--timeout-s", "150"},
                 dir_ / "launch.log");
    const auto status = launch.wait(170.0);
    std::cout << "secure swa_launch through " << vehicle << ", " << uavs
              << " UAVs, 30 s simulated: " << secondsSince(t0) << " s wall\n";
    const std::string log = readFile(dir_ / "launch.log");
    ASSERT_TRUE(status.has_value()) << log;
    EXPECT_EQ(*status, 0) << log << allLogs(out / "logs");
    const std::string summary = readFile(out / "summary.json");
    EXPECT_NEAR(jsonNumber(summary, "mean_neighbor_distance_m"), 10.0, 1.0) << summary;
    EXPECT_EQ(jsonNumber(summary, "collisions"), 0.0) << summary;
    const std::string events = readFile(out / "events.csv");
    for (int i = 0; i < uavs; ++i) {
      EXPECT_NE(events.find(engaged(i)), std::string::npos) << events << allLogs(out / "logs");
    }
    expectNothingLeft();
  }

  void expectNothingLeft() {
    EXPECT_TRUE(processesOnDomain(domain_).empty()) << "processes left on domain " << domain_;
    std::string left;
    for (const std::string& f : ofDomain(janitor_.zombies(), domain_)) left += " " + f;
    EXPECT_TRUE(left.empty()) << "shared-memory files left behind:" << left;
  }

  OwnShm own_shm_;      // first: this test's /dev/shm is its own (private_shm.h)
  ShmJanitor janitor_;  // outlives every process and participant of the test
  fs::path dir_;
  fs::path creds_;
  std::vector<fs::path> made_;
  int domain_ = testDomain(53);
};

// (a) swa_launch --secure: the 4-UAV dropout scenario for 30 s stays cohesive. An unauthenticated observer reading
// the ground truth during the run proves that the run really was secured (it must get nothing).
TEST_F(SecurityTest, SecureLaunchStaysCohesive) {
  // GIVEN this test's credentials, and an observer without credentials reading the ground truth
  std::atomic<int> observed{0};
  auto observer = makeParticipant("swa_test_observer", domain_, std::nullopt);
  auto truth = observer->reader<msg::SwarmTruthPubSubType>(dds::topics::kTruth, dds::qos::kTruthReader,
                                                           [&observed](msg::SwarmTruth&&) { ++observed; });
  // WHEN swa_launch --secure runs the 4-UAV GNSS-loss scenario for 30 s
  const fs::path out = dir_ / "out";
  const auto t0 = SteadyClock::now();
  Child launch({kLaunch, "--secure", creds_.string(), "--scenario", kScenario, "--set", "duration_s=30", "--domain",
                std::to_string(domain_), "--out", out.string(), "--timeout-s", "150"},
               dir_ / "launch.log");
  // THEN it exits with PASS
  const auto status = launch.wait(170.0);
  std::cout << "secure swa_launch, dropout_4, 30 s simulated: " << secondsSince(t0) << " s wall\n";
  const std::string log = readFile(dir_ / "launch.log");
  ASSERT_TRUE(status.has_value()) << log;
  EXPECT_EQ(*status, 0) << log << allLogs(out / "logs");

  // AND the swarm stayed cohesive: d_NB within 10 % of r, no collision
  const std::string summary = readFile(out / "summary.json");
  ASSERT_FALSE(summary.empty()) << log;
  EXPECT_NEAR(jsonNumber(summary, "mean_neighbor_distance_m"), 10.0, 1.0) << "d_NB within ±10 % of r = 10 m";
  EXPECT_EQ(jsonNumber(summary, "collisions"), 0.0) << summary;
  // AND the unauthenticated observer matched nothing and received nothing: the run really was secured
  EXPECT_EQ(truth.matched(), 0) << "an unauthenticated reader matched the secure simulator's truth writer";
  EXPECT_EQ(observed.load(), 0) << "an unauthenticated reader received ground truth";
  // AND nothing of the run is left
  observer.reset();
  expectNothingLeft();
}

// (a') The same through PX4: the simulator as every UAV's PX4, every vehicle engaged offboard.
TEST_F(SecurityTest, SecureLaunchThroughPx4StaysCohesive) {
  secureLaunchThroughAutopilot("px4", kUavs,
                               [](int i) { return "PX4 stand-in " + dds::topics::px4Namespace(i) + ": OFFBOARD"; });
}

// (a'') And through ArduPilot: the simulator as every UAV's ArduPilot, the bridges' permissions covering its topics and
// its arm / mode services both ways; every vehicle switched to GUIDED through mode_switch. 3 UAVs: fewer participants,
// fewer handshakes that Fast DDS 2.9 may stall (deploy/README.md). By hand on 2026-11-28: 3 UAVs 5 of 5 (GUIDED 10
// and 17 s late in two, before the bridge watched its requests' endpoints too), then 6 of 6 by ctest; 4 UAVs 4 of 6
// before that watch, then 6 of 6, then 1 of 8 failed (a broken bridge-to-agent channel), then 8 of 8 once the bridge
// re-creates its participant when its agent is lost with everything matched.
TEST_F(SecurityTest, SecureLaunchThroughArdupilotStaysCohesive) {
  secureLaunchThroughAutopilot("ardupilot", 3, [](int i) {
    return "ArduPilot stand-in " + dds::topics::apNamespace(i) + ": GUIDED on request";
  });
}

// (b) The permissions of UAV 2 do not reach UAV 1's topics: no reader of its detections, no writer of its
// commands. Its own topics work with the same participant (positive control).
TEST_F(SecurityTest, Uav2CredentialsCannotReadOrCommandUav1) {
  // GIVEN a participant with UAV 2's credentials
  auto uav2 = makeParticipant("swa_agent_2", domain_, creds_);
  // THEN it can read its own detections and write its own commands (positive control)
  EXPECT_EQ(tryCreate(*uav2, Kind::kReader, dds::topics::detections(2)), "") << "own detections must be readable";
  EXPECT_EQ(tryCreate(*uav2, Kind::kWriter, dds::topics::cmdVel(2)), "") << "own commands must be writable";

  // WHEN it tries to read UAV 1's detections or write UAV 1's commands THEN the middleware refuses, naming the topic
  EXPECT_THROW(createEndpoint(*uav2, Kind::kReader, dds::topics::detections(1)), dds::DdsError);
  EXPECT_THROW(createEndpoint(*uav2, Kind::kWriter, dds::topics::cmdVel(1)), dds::DdsError);
  const std::string why = tryCreate(*uav2, Kind::kReader, dds::topics::detections(1));
  EXPECT_NE(why.find("swa/uav1/detections"), std::string::npos) << why;

  // AND it is still usable after the refusals
  EXPECT_EQ(tryCreate(*uav2, Kind::kReader, dds::topics::imu(2)), "");
  uav2.reset();
  // AND nothing is left
  expectNothingLeft();
}

// Issue #46: through an autopilot an agent's IMU comes from its bridge and its detections from another peer. In a
// secure launch through PX4 (N = 8, 1 run in 50) a re-created agent authenticated its bridge but never the simulator:
// its IMU flowed, no detection came, and its UAV left SWA's control. An IMU without a detection source is no start:
// the agent re-creates its participant as for any stalled handshake.
TEST_F(SecurityTest, AgentWithItsImuButNoDetectionSourceReCreatesItsParticipant) {
  // GIVEN agent 1, secured, and UAV 1's bridge in this process, which writes its IMU samples and reads its commands;
  // no detection source on the domain (from the agent, a handshake with one that never completes looks the same)
  const fs::path log = dir_ / "agent1.log";
  auto agent = startAgent(1, "agent1.log");
  auto bridge = makeParticipant("swa_bridge_1", domain_, creds_);
  std::atomic<int> commands{0};
  dds::Writer<msg::Imu> imu = bridge->writer<msg::ImuPubSubType>(dds::topics::imu(1), dds::qos::kSensorWriter);
  bridge->reader<msg::VelocitySetpointPubSubType>(dds::topics::cmdVel(1), dds::qos::kCommandReader,
                                                  [&commands](msg::VelocitySetpoint&&) { ++commands; });
  ASSERT_TRUE(waitFor([&] { return imu.matched() > 0; }, 30.0)) << readFile(log);
  // WHEN IMU samples flow at 100 Hz
  const std::string why =
      "swa_agent 1: no reader of swa/uav1/cmd_vel or no writer of swa/uav1/detections with DDS "
      "Security on (a stalled authentication handshake";
  bool recreated = false;
  for (std::uint32_t k = 0; k < 3000 && !recreated; ++k) {
    msg::Imu m = restingImu(1, static_cast<std::int64_t>(k) * 10'000'000, k + 1);
    imu.write(m);
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    if (k % 50 == 49) recreated = readFile(log).find(why) != std::string::npos;
  }
  // THEN the agent answers them, and still re-creates its participant for want of a detection source, saying so
  EXPECT_GT(commands.load(), 0) << readFile(log);
  EXPECT_TRUE(recreated) << readFile(log);
  EXPECT_EQ(agent->stop(), 0) << readFile(log);
  bridge.reset();
  expectNothingLeft();
}

// Every role against what it must and must not be able to create (make-credentials.sh --help, the table).
TEST_F(SecurityTest, EachRoleCreatesExactlyTheEndpointsItsPermissionsGrant) {
  // GIVEN every role's credentials (agent, simulator, autopilot bridge, monitor) and what each must and must not
  // create (make-credentials.sh --help, the table)
  using dds::topics::apNamespace;
  using dds::topics::apReply;
  using dds::topics::apRequest;
  using dds::topics::apTopic;
  using dds::topics::bridgeState;
  using dds::topics::cmdVel;
  using dds::topics::detections;
  using dds::topics::gnss;
  using dds::topics::imu;
  using dds::topics::px4In;
  using dds::topics::px4Namespace;
  using dds::topics::px4Out;
  using dds::topics::sensors;
  using dds::topics::state;
  struct Endpoint {
    Kind kind;
    std::string topic;
  };
  struct Role {
    std::string name;
    std::vector<Endpoint> allowed, denied;
  };
  const std::string truth = dds::topics::kTruth, events = dds::topics::kEvents, clock = dds::topics::kClock;
  const Kind R = Kind::kReader, W = Kind::kWriter;
  const std::vector<Role> roles{
      {"swa_agent_2",
       {{R, imu(2)}, {R, detections(2)}, {R, gnss(2)}, {R, sensors(2)}, {R, clock}, {W, cmdVel(2)}, {W, state(2)}},
       {{R, imu(1)},
        {R, detections(1)},
        {R, gnss(3)},
        {R, sensors(1)},
        {R, state(1)},
        {R, cmdVel(2)},
        {R, truth},
        {R, events},
        {W, cmdVel(1)},
        {W, state(1)},
        {W, imu(2)},
        {W, detections(2)},
        {W, sensors(2)},
        {W, clock},
        {W, truth}}},
      {"swa_sim",
       {{W, imu(0)},
        {W, detections(3)},
        {W, gnss(12)},
        {W, sensors(5)},
        {W, truth},
        {W, events},
        {W, clock},
        {R, cmdVel(1)},
        {W, px4Out(px4Namespace(3), "vehicle_attitude")},
        {W, px4Out(px4Namespace(0), "vehicle_status")},
        {W, px4Out(px4Namespace(2), "vehicle_status_v1")},
        {R, px4In(px4Namespace(2), "trajectory_setpoint")},
        {R, px4In(px4Namespace(1), "offboard_control_mode")},
        {W, apTopic(apNamespace(3), "imu/experimental/data")},
        {W, apTopic(apNamespace(0), "status")},
        {R, apTopic(apNamespace(2), "cmd_vel")},
        {R, apRequest(apNamespace(1), "mode_switch")},
        {W, apReply(apNamespace(1), "mode_switch")}},
       {{R, imu(0)},
        {R, detections(0)},
        {R, sensors(0)},
        {W, cmdVel(0)},
        {W, state(0)},
        {R, state(0)},
        {R, truth},
        {R, clock},
        {R, px4Out(px4Namespace(0), "vehicle_attitude")},
        {W, px4In(px4Namespace(0), "trajectory_setpoint")}}},
      // The autopilot bridge of UAV 1: its sensors out, its commands and its agent's state in, its own PX4's topics
      // (its odometry included: issue #43), nothing of another UAV or vehicle.
      {"swa_bridge_1",
       {{W, imu(1)},
        {W, detections(1)},
        {W, gnss(1)},
        {R, cmdVel(1)},
        {R, state(1)},
        {W, bridgeState(1)},
        {R, px4Out(px4Namespace(1), "vehicle_attitude")},
        {R, px4Out(px4Namespace(1), "vehicle_status")},
        {R, px4Out(px4Namespace(1), "vehicle_status_v1")},
        {W, px4In(px4Namespace(1), "trajectory_setpoint")},
        {W, px4In(px4Namespace(1), "offboard_control_mode")},
        {W, px4In(px4Namespace(1), "vehicle_visual_odometry")},
        {R, apTopic(apNamespace(1), "imu/experimental/data")},
        {R, apTopic(apNamespace(1), "status")},
        {W, apTopic(apNamespace(1), "cmd_vel")},
        {W, apTopic(apNamespace(1), "tf")},
        {W, apRequest(apNamespace(1), "arm_motors")},
        {R, apReply(apNamespace(1), "arm_motors")}},
       {{W, imu(2)},
        {W, detections(0)},
        {W, sensors(1)},
        {R, imu(1)},
        {R, cmdVel(2)},
        {W, cmdVel(1)},
        {R, state(2)},
        {W, state(1)},
        {W, px4In(px4Namespace(2), "vehicle_visual_odometry")},
        {W, apTopic(apNamespace(0), "tf")},
        {R, truth},
        {W, truth},
        {W, clock},
        {W, bridgeState(2)},
        {R, px4Out(px4Namespace(2), "vehicle_attitude")},
        {W, px4In(px4Namespace(0), "trajectory_setpoint")},
        {W, px4Out(px4Namespace(1), "vehicle_attitude")},
        {R, px4In(px4Namespace(1), "trajectory_setpoint")},
        {R, px4Out(px4Namespace(2), "vehicle_status_v1")},
        {R, apTopic(apNamespace(2), "imu/experimental/data")},
        {W, apTopic(apNamespace(0), "cmd_vel")},
        {W, apTopic(apNamespace(1), "status")},
        {R, apTopic(apNamespace(1), "cmd_vel")},
        {W, apRequest(apNamespace(2), "mode_switch")},
        {R, apRequest(apNamespace(1), "arm_motors")}}},
      {"swa_monitor",
       {{R, truth},
        {R, events},
        {R, state(0)},
        {R, state(3)},
        {R, imu(0)},
        {R, detections(2)},
        {R, sensors(1)},
        {R, cmdVel(1)},
        {R, clock}},
       {{W, truth}, {W, events}, {W, state(0)}, {W, imu(0)}, {W, sensors(0)}, {W, cmdVel(0)}, {W, clock}}},
  };
  for (const Role& role : roles) {
    // WHEN a participant with the role's credentials creates each endpoint
    auto p = makeParticipant(role.name, domain_, creds_);
    // THEN every allowed one is created and every denied one refused
    for (const Endpoint& e : role.allowed) {
      EXPECT_EQ(tryCreate(*p, e.kind, e.topic), "")
          << role.name << " must be able to create a " << kindName(e.kind) << " on " << e.topic;
    }
    for (const Endpoint& e : role.denied) {
      EXPECT_NE(tryCreate(*p, e.kind, e.topic), "")
          << role.name << " must not be able to create a " << kindName(e.kind) << " on " << e.topic;
    }
  }
  // AND nothing is left
  expectNothingLeft();
}

// (c) A participant without credentials, next to a running secure simulator and its agents (realtime clock, so
// sensor samples flow all the time), matches none of their endpoints and receives nothing. Positive controls: a
// participant with UAV 1's credentials, created the same way in the same process, matches both and receives UAV 1's
// sensor frames; and the unsecured reader does match an unsecured writer added afterwards.
TEST_F(SecurityTest, ParticipantWithoutCredentialsMatchesNothing) {
  // GIVEN a secure simulator (realtime clock) and its 4 agents, all discovered
  std::vector<std::unique_ptr<Child>> agents;
  for (int i = 0; i < kUavs; ++i) agents.push_back(startAgent(i, "agent" + std::to_string(i) + ".log"));
  Child sim({kSim, "--scenario", kScenario, "--set", "clock.mode=realtime", "--set", "duration_s=600", "--domain",
             std::to_string(domain_), "--startup-timeout-s", "60"},
            dir_ / "sim.log", {securityEnv()});
  const auto t0 = SteadyClock::now();
  ASSERT_TRUE(waitFor([&] { return readFile(dir_ / "sim.log").find("discovered in") != std::string::npos; }, 60.0))
      << readFile(dir_ / "sim.log") << runLogs(dir_, kUavs);
  std::cout << "secure sim + 4 agents discovered: " << secondsSince(t0) << " s\n";

  // WHEN a participant without credentials and one with UAV 1's (the control) read UAV 1's sensor frames and write its
  // commands
  std::atomic<int> intruder_samples{0}, control_samples{0};
  auto intruder = makeParticipant("swa_intruder", domain_, std::nullopt);
  auto intruder_imu = intruder->reader<msg::SensorFramePubSubType>(dds::topics::sensors(1), dds::qos::kFrameReader,
                                                                   [&](msg::SensorFrame&&) { ++intruder_samples; });
  auto intruder_cmd =
      intruder->writer<msg::VelocitySetpointPubSubType>(dds::topics::cmdVel(1), dds::qos::kCommandWriter);
  // The control recovers from a stalled authentication handshake as an agent does (swa/dds/handshake_watch.h): Fast
  // DDS 2.9 now and then never completes one pair's (deploy/README.md; seen here in CI: the control matched nothing in
  // 20 s). That is the product's own reconnection, which a user's node gets too, not a retry of the check.
  std::unique_ptr<dds::Participant> control;
  dds::Reader<msg::SensorFrame> control_imu;
  dds::Writer<msg::VelocitySetpoint> control_cmd;
  dds::HandshakeWatch control_watch(true);
  const auto connectControl = [&] {
    control.reset();
    control = makeParticipant("swa_agent_1", domain_, creds_);
    control_imu = control->reader<msg::SensorFramePubSubType>(dds::topics::sensors(1), dds::qos::kFrameReader,
                                                              [&](msg::SensorFrame&&) { ++control_samples; });
    control_cmd = control->writer<msg::VelocitySetpointPubSubType>(dds::topics::cmdVel(1), dds::qos::kCommandWriter);
    control_watch.connected(SteadyClock::now());
  };
  connectControl();

  // THEN the control matches both and receives samples; once it has, the intruder has had the same time to do so
  const auto t1 = SteadyClock::now();
  const bool control_ok = waitFor(
      [&] {
        const bool matched = control_imu.matched() >= 1 && control_cmd.matched() >= 1;
        if (matched && control_samples.load() > 10) return true;
        if (control_watch.stalled(control_samples.load() > 0, matched, SteadyClock::now(),
                                  control->lastAuthentication())) {
          connectControl();
        }
        return false;
      },
      60.0);
  std::cout << "secured control matched and received after " << secondsSince(t1) << " s, " << control_watch.reconnects()
            << " reconnection(s)\n";
  std::this_thread::sleep_for(std::chrono::seconds(3));
  EXPECT_TRUE(control_ok) << "control: imu matched " << control_imu.matched() << ", cmd_vel matched "
                          << control_cmd.matched() << ", samples " << control_samples.load() << "\n"
                          << readFile(dir_ / "sim.log");
  // AND the intruder matched nothing and received nothing
  EXPECT_EQ(intruder_imu.matched(), 0) << "an unauthenticated reader matched swa/uav1/sensors";
  EXPECT_EQ(intruder_cmd.matched(), 0) << "an unauthenticated writer matched swa/uav1/cmd_vel";
  EXPECT_EQ(intruder_samples.load(), 0) << "an unauthenticated reader received sensor frames";
  std::cout << "intruder: matched " << intruder_imu.matched() << " / " << intruder_cmd.matched() << ", samples "
            << intruder_samples.load() << "; control: samples " << control_samples.load() << "\n";

  // AND the intruder itself can match: an unsecured peer's writer on the same topic is found within seconds
  auto peer = makeParticipant("swa_intruder_peer", domain_, std::nullopt);
  auto peer_imu = peer->writer<msg::SensorFramePubSubType>(dds::topics::sensors(1), dds::qos::kFrameWriter);
  EXPECT_TRUE(waitFor([&] { return intruder_imu.matched() == 1 && peer_imu.matched() == 1; }, 10.0))
      << "the unsecured reader did not even match an unsecured writer: intruder " << intruder_imu.matched() << ", peer "
      << peer_imu.matched();
  peer.reset();

  // WHEN everything is stopped THEN the simulator exits as interrupted, every agent cleanly, and nothing is left
  control.reset();
  intruder.reset();
  EXPECT_EQ(sim.stop(), 1) << "interrupted simulator: exit 1";  // SIGTERM before the end of the scenario
  for (auto& a : agents) EXPECT_EQ(a->stop(), 0);
  expectNothingLeft();
}

// Runs swa_agent --id 1 with the credentials as they are now; expects a refusal within seconds that names `cause`
// (swa::dds::credentialProblem's sentence). Returns its log.
std::string expectRefusedAtStart(const std::function<std::unique_ptr<Child>()>& start, const fs::path& log,
                                 const std::string& what, const std::string& cause) {
  const auto t0 = SteadyClock::now();
  auto agent = start();
  const auto status = agent->wait(20.0);
  const double took = secondsSince(t0);
  std::cout << what << ": swa_agent exit " << (status ? std::to_string(*status) : "none") << " after " << took
            << " s\n";
  const std::string text = readFile(log);
  EXPECT_TRUE(status.has_value()) << what << ": the agent still runs after 20 s\n" << text;
  EXPECT_EQ(status, std::optional<int>(1)) << what << "\n" << text;
  EXPECT_LT(took, 10.0) << what;
  EXPECT_NE(text.find(kRefused), std::string::npos) << what << "\n" << text;
  EXPECT_NE(text.find(cause), std::string::npos) << what << ": cause not named (" << cause << ")\n" << text;
  EXPECT_EQ(text.find("up on domain"), std::string::npos) << what << "\n" << text;
  return text;
}

// The untampered credentials start: the agent is up (participant and endpoints created) and stops cleanly.
void expectStarts(Child& agent, const fs::path& log) {
  const bool up = waitFor([&] { return readFile(log).find("swa_agent 1: up on domain") != std::string::npos; }, 20.0);
  EXPECT_TRUE(up) << readFile(log);
  EXPECT_FALSE(agent.wait(0.0).has_value()) << readFile(log);
  EXPECT_EQ(agent.stop(), 0) << readFile(log);
}

// (d) One byte of swa_agent_1/permissions.p7s changed — 'swa/uav1/cmd_vel' widened to 'swa/uav*/cmd_vel', the
// attack a tampered file would attempt — and, separately, one byte of the signature: the agent is refused at start
// with a message naming the file and its signature as the cause. The untampered file starts (positive control).
TEST_F(SecurityTest, TamperedPermissionsAreRefusedAtStart) {
  // GIVEN UAV 1's genuine permissions, a byte of the grant swa/uav1/cmd_vel and one well inside the signature
  const fs::path file = creds_ / "swa_agent_1" / "permissions.p7s";
  const std::string original = readFile(file);
  const std::size_t grant = original.find("swa/uav1/cmd_vel");
  ASSERT_NE(grant, std::string::npos) << original;
  // The last mention is the signature part's own Content-Type (the first is the message's protocol parameter).
  const std::size_t signature = original.rfind("pkcs7-signature");
  ASSERT_NE(signature, std::string::npos) << original;
  // A base64 character well inside the signature block (past its MIME headers).
  const std::size_t sig_body = original.find("\n\n", signature);
  ASSERT_NE(sig_body, std::string::npos) << original;
  const std::size_t sig_byte = sig_body + 40;
  ASSERT_LT(sig_byte, original.size());

  // WHEN the file is changed in either byte (the grant widened to swa/uav*/cmd_vel, or the signature) and swa_agent 1
  // starts with it THEN it is refused within seconds, naming the file and its signature as the cause
  struct Case {
    std::string what;
    std::size_t at;
    char replacement;
    std::string cause;
  };
  // The changed signature byte may leave no readable S/MIME document or one whose signature fails: either way the
  // sentence starts the same.
  const std::string bad_signature =
      "signature of " + file.string() + " does not verify against " + (creds_ / "ca.pem").string();
  const char sig_replacement = original[sig_byte] == 'A' ? 'B' : 'A';
  for (const Case& c :
       {Case{"grant widened to swa/uav*/cmd_vel", grant + 7, '*',
             bad_signature + " (modified after signing, or signed by another CA; OpenSSL: digest failure)"},
        Case{"signature byte changed", sig_byte, sig_replacement, bad_signature}}) {
    std::string tampered = original;
    tampered[c.at] = c.replacement;
    ASSERT_NE(tampered, original);
    std::ofstream(file, std::ios::binary | std::ios::trunc) << tampered;
    const std::string log_name = "agent1_" + std::to_string(c.at) + ".log";
    const std::string text =
        expectRefusedAtStart([&] { return startAgent(1, log_name); }, dir_ / log_name, c.what, c.cause);
    std::cout << "---- " << c.what << ", swa_agent output:\n" << text << "----\n";
  }

  // WHEN the genuine file is back THEN the agent starts and stops cleanly (positive control), and nothing is left
  std::ofstream(file, std::ios::binary | std::ios::trunc) << original;
  auto agent = startAgent(1, "agent1_original.log");
  expectStarts(*agent, dir_ / "agent1_original.log");
  expectNothingLeft();
}

// (d, continued) Validly signed permissions that are not UAV 1's: UAV 2's document (another subject), and UAV 1's
// document from another CA (an attacker's own). Both refused at start; the right one starts.
TEST_F(SecurityTest, ForeignPermissionsAreRefusedAtStart) {
  // GIVEN UAV 1's genuine permissions, and credentials of another CA
  const fs::path file = creds_ / "swa_agent_1" / "permissions.p7s";
  const std::string original = readFile(file);
  const fs::path other = dir_ / "other_ca";
  ASSERT_TRUE(makeCredentials(other));

  // WHEN UAV 1's permissions are replaced by UAV 2's (another subject) or by UAV 1's of the other CA, and
  // swa_agent 1 starts with them THEN it is refused within seconds, naming the file and the cause
  struct Case {
    std::string what;
    fs::path source;
    std::string cause;
  };
  const std::vector<Case> cases{
      {"UAV 2's permissions as UAV 1's", creds_ / "swa_agent_2" / "permissions.p7s",
       file.string() + " grants subject 'CN=swa_agent_2,O=SWA' but " + (creds_ / "swa_agent_1" / "cert.pem").string() +
           " is 'CN=swa_agent_1,O=SWA'"},
      {"UAV 1's permissions signed by another CA", other / "swa_agent_1" / "permissions.p7s",
       "signature of " + file.string() + " does not verify against " + (creds_ / "ca.pem").string() +
           " (modified after signing, or signed by another CA; OpenSSL: certificate verify error"}};
  int n = 0;
  for (const auto& [what, source, cause] : cases) {
    std::ofstream(file, std::ios::binary | std::ios::trunc) << readFile(source);
    const std::string log_name = "agent1_foreign" + std::to_string(n++) + ".log";
    const std::string text =
        expectRefusedAtStart([&] { return startAgent(1, log_name); }, dir_ / log_name, what, cause);
    std::cout << "---- " << what << ", swa_agent output:\n" << text << "----\n";
  }

  // WHEN the genuine file is back THEN the agent starts and stops cleanly (positive control), and nothing is left
  std::ofstream(file, std::ios::binary | std::ios::trunc) << original;
  auto agent = startAgent(1, "agent1_original.log");
  expectStarts(*agent, dir_ / "agent1_original.log");
  expectNothingLeft();
}

}  // namespace
}  // namespace swa::testing

// The ROS 2 wire profile (SWA_NAMING=ros2, issue #13) seen from the wire, without a ROS installation: a 4-UAV launch
// in the ros2 naming on a quiet private domain, with
//   - an observer that collects every reader and writer through DDS discovery: every SWA endpoint's topic is the ROS
//     mapping (rt/ + a valid ROS name) and its type the ROS DDS name of a message of idl/swa_msgs (or
//     geometry_msgs/TwistStamped); the isolation audit holds under these names too;
//   - readers that keep the raw payloads of every topic under the ROS type names: each decodes with the generated
//     code, carries XCDR1 (classic little-endian CDR), and is written with the C++ decoding as JSON to
//     $SWA_ROS2_CAPTURE (default: the test's directory, kept), where tests/ros2/decode_check.mjs decodes it again with
//     an independent ROS 2 CDR implementation against the .msg files (tests/ros2/test_ros2_decode.sh runs both).

#include <signal.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <memory>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <swa/msg/AgentStatePubSubTypes.h>
#include <swa/msg/ClockPubSubTypes.h>
#include <swa/msg/DetectionsPubSubTypes.h>
#include <swa/msg/GnssFixPubSubTypes.h>
#include <swa/msg/ImuPubSubTypes.h>
#include <swa/msg/ScenarioEventPubSubTypes.h>
#include <swa/msg/SwarmMetricsPubSubTypes.h>
#include <swa/msg/SwarmTruthPubSubTypes.h>
#include <swa/msg/VelocitySetpointPubSubTypes.h>
#include <swa/ros/TwistStampedPubSubTypes.h>

#include "../integration/discovery_observer.h"
#include "../integration/process_test.h"
#include "msg_json.h"
#include "raw_capture.h"
#include "swa/dds/naming.h"
#include "swa/dds/topics.h"

namespace swa::testing {
namespace {

using ros2::Bytes;
using ros2::json;

const std::string kScenario = std::string(SWA_SOURCE_DIR) + "/deploy/scenarios/dropout_4.yaml";
const fs::path kMsgDir = fs::path(SWA_SOURCE_DIR) / "idl" / "swa_msgs" / "msg";
constexpr int kUavs = 4;
constexpr double kRunBoundS = 120.0;
constexpr double kLateDiscoveryS = 10.0;

const dds::WireNames kRos2{dds::Naming::kRos2, ""};

// One SWA topic of the run: its SWA name, the generated type, and how a payload of it becomes JSON.
struct TopicSpec {
  std::string swa_topic;
  std::string generated_type;
  std::function<std::optional<json>(const Bytes&)> to_json;
};

template <class PubSubType>
TopicSpec spec(const std::string& topic) {
  return {topic, PubSubType().getName(), [](const Bytes& b) -> std::optional<json> {
            typename PubSubType::type m;
            if (!ros2::decode<PubSubType>(b, m)) return std::nullopt;
            return ros2::toJson(m);
          }};
}

std::vector<TopicSpec> runTopics() {
  std::vector<TopicSpec> t;
  for (int i = 0; i < kUavs; ++i) {
    t.push_back(spec<msg::ImuPubSubType>(dds::topics::imu(i)));
    t.push_back(spec<msg::DetectionsPubSubType>(dds::topics::detections(i)));
    t.push_back(spec<msg::GnssFixPubSubType>(dds::topics::gnss(i)));
    t.push_back(spec<msg::VelocitySetpointPubSubType>(dds::topics::cmdVel(i)));
    t.push_back(spec<geometry_msgs::msg::TwistStampedPubSubType>(dds::topics::cmdVelStamped(i)));
    t.push_back(spec<msg::AgentStatePubSubType>(dds::topics::state(i)));
  }
  t.push_back(spec<msg::SwarmTruthPubSubType>(dds::topics::kTruth));
  t.push_back(spec<msg::ScenarioEventPubSubType>(dds::topics::kEvents));
  t.push_back(spec<msg::ClockPubSubType>(dds::topics::kClock));
  return t;
}

std::string hex(const Bytes& b) {
  std::ostringstream s;
  for (const std::uint8_t x : b) s << std::hex << std::setw(2) << std::setfill('0') << static_cast<int>(x);
  return s.str();
}

// Why `e` (an endpoint of an SWA process) does not follow the ROS 2 mapping, if it does not.
std::optional<std::string> rosNameProblem(const Endpoint& e) {
  const std::optional<std::string> topic = dds::rosTopicOf(e.topic);
  if (!topic) return "topic " + e.topic + " lacks the rt/ prefix: ROS tools drop it";
  if (!dds::isValidRosTopic(*topic)) return "topic " + e.topic + " is not the mapping of a valid ROS name";
  const std::optional<std::string> type = dds::rosTypeOf(e.type);
  if (!type) return "type " + e.type + " is not pkg::msg::dds_::Name_";
  if (*type == "geometry_msgs/msg/TwistStamped") return std::nullopt;
  const std::string prefix = "swa_msgs/msg/";
  if (type->rfind(prefix, 0) != 0 || !fs::exists(kMsgDir / (type->substr(prefix.size()) + ".msg"))) {
    return "type " + e.type + " (" + *type + ") is neither a message of idl/swa_msgs nor a standard ROS type";
  }
  return std::nullopt;
}

// The endpoints with their SWA topic names (the ros2 mapping undone), for the isolation audit.
std::vector<Endpoint> swaNamed(std::vector<Endpoint> endpoints) {
  for (Endpoint& e : endpoints) {
    if (const auto topic = dds::swaTopic(kRos2, e.topic)) e.topic = *topic;
  }
  return endpoints;
}

class Ros2ProfileRun : public ProcessRun {
 protected:
  void SetUp() override {
    dir_ = freshTestDir("swa_ros2_profile");
    observer_ = observeQuietDomain(domain_, "swa_test_ros2_observer");
    ASSERT_TRUE(observer_) << "no quiet DDS domain found";
    useOwnSwarm();
    ::setenv("SWA_NAMING", "ros2", 1);
  }
  void TearDown() override {
    launch_.reset();
    ProcessRun::TearDown();
    ::unsetenv("SWA_NAMING");
  }
  void stopObservers() override {
    capture_.reset();
    observer_.reset();
  }

  std::unique_ptr<DiscoveryObserver> observer_;
  std::unique_ptr<ros2::RawCapture> capture_;
  std::unique_ptr<Child> launch_;
};

TEST_F(Ros2ProfileRun, EveryEndpointHasItsRosNameAndEveryPayloadDecodes) {
  // GIVEN readers of the raw payloads of every topic of a 4-UAV run under the names the ROS mapping gives
  const std::vector<TopicSpec> topics = runTopics();
  capture_ = std::make_unique<ros2::RawCapture>(domain_, 2, 3);
  for (const TopicSpec& t : topics) {
    // The clock is the one VOLATILE writer (idl/runtime/dds/profiles.xml).
    capture_->read(dds::ddsTopic(kRos2, t.swa_topic), dds::ddsType(kRos2, t.generated_type),
                   t.swa_topic != dds::topics::kClock);
  }

  // WHEN swa_launch runs the GNSS-loss scenario for 12 s in the ros2 naming (lockstep; GNSS is lost at 10 s)
  launch_ = std::make_unique<Child>(
      std::vector<std::string>{SWA_LAUNCH_BINARY, "--scenario", kScenario, "--set", "duration_s=12", "--domain",
                               std::to_string(domain_), "--out", (dir_ / "run").string(), "--naming", "ros2"},
      dir_ / "launch.log");
  const std::optional<int> status = launch_->wait(kRunBoundS);
  const std::string log = readFile(dir_ / "launch.log");
  ASSERT_TRUE(status) << "swa_launch still running after " << kRunBoundS << " s\n" << log;
  // THEN the run completed (PASS or FAIL is the scenario's business, not the naming's)
  ASSERT_TRUE(*status == 0 || *status == 1) << "exit " << *status << "\n" << log;

  // THEN every endpoint of every SWA process follows the ROS 2 mapping
  waitFor([&] { return auditAgentEndpoints(swaNamed(observer_->log().endpoints()), kUavs).empty(); }, kLateDiscoveryS);
  const std::vector<Endpoint> endpoints = observer_->log().endpoints();
  const std::string table = endpointTable(endpoints);
  std::cout << endpoints.size() << " endpoints discovered:\n" << table;
  std::size_t swa_endpoints = 0;
  for (const Endpoint& e : endpoints) {
    if (e.participant.rfind("swa_test_", 0) == 0) continue;  // this test's own
    ++swa_endpoints;
    if (const auto problem = rosNameProblem(e)) ADD_FAILURE() << e.participant << ": " << *problem;
  }
  // ... and there were all of them: 6 per agent, the simulator's 4 per UAV and 3 of its own, the monitor's
  EXPECT_GE(swa_endpoints, static_cast<std::size_t>(6 * kUavs + 4 * kUavs + 3 + kUavs + 2)) << table;
  // ... and under these names no agent reads what another writes or anything outside its own namespace
  const std::vector<Endpoint> as_swa = swaNamed(endpoints);
  const std::vector<std::string> violations = auditIsolation(as_swa);
  EXPECT_TRUE(violations.empty()) << violations.front();
  const std::vector<std::string> incomplete = auditAgentEndpoints(as_swa, kUavs);
  EXPECT_TRUE(incomplete.empty()) << incomplete.front() << "\n" << table;

  // THEN every topic delivered payloads under its ROS type name; each is classic little-endian CDR (XCDR1: 00 01) and
  // decodes with the generated code; they are written out for the independent decoder
  const std::map<std::string, std::vector<Bytes>> payloads = capture_->payloads();
  json capture = json::array();
  for (const TopicSpec& t : topics) {
    const std::string dds_topic = dds::ddsTopic(kRos2, t.swa_topic);
    const auto it = payloads.find(dds_topic);
    if (it == payloads.end() || it->second.empty()) {
      ADD_FAILURE() << "nothing received on " << dds_topic << " as " << dds::ddsType(kRos2, t.generated_type);
      continue;
    }
    for (const Bytes& b : it->second) {
      ASSERT_GE(b.size(), 4u) << dds_topic;
      EXPECT_EQ(hex(Bytes(b.begin(), b.begin() + 4)), "00010000") << dds_topic << ": not XCDR1 little endian";
      const std::optional<json> decoded = t.to_json(b);
      ASSERT_TRUE(decoded) << dds_topic << ": does not decode";
      capture.push_back({{"topic", dds_topic},
                         {"ros_type", *dds::rosTypeOf(dds::ddsType(kRos2, t.generated_type))},
                         {"captured", true},
                         {"cdr_hex", hex(b)},
                         {"expected", *decoded}});
    }
  }
  // SwarmMetrics has no publisher in a run: its payload as a DataWriter would serialize it
  msg::SwarmMetrics metrics;
  metrics.header().stamp_ns(-1'500'000'001);
  metrics.header().seq(7);
  metrics.mean_neighbor_distance_m(9.75);
  metrics.centroid_drift_mps(0.0125);
  metrics.min_separation_m(3.5);
  metrics.collisions(2);
  metrics.spread_m(21.25);
  metrics.groups(1);
  metrics.formation_error_m(0.5);
  metrics.anees_position(2.125);
  metrics.anees_velocity(1.875);
  metrics.anees_band_low(1.6);
  metrics.anees_band_high(2.4);
  metrics.live_agents(8);
  capture.push_back({{"topic", "(serialized, no publisher)"},
                     {"ros_type", "swa_msgs/msg/SwarmMetrics"},
                     {"captured", false},
                     {"cdr_hex", hex(ros2::encode<msg::SwarmMetricsPubSubType>(metrics))},
                     {"expected", ros2::toJson(metrics)}});

  const char* out_env = std::getenv("SWA_ROS2_CAPTURE");
  const fs::path out = out_env != nullptr && *out_env != '\0' ? fs::path(out_env) : dir_ / "capture.json";
  std::ofstream(out) << capture.dump(1) << "\n";
  std::cout << capture.size() << " payloads written to " << out << "\n";
  EXPECT_FALSE(HasFailure()) << log;
}

}  // namespace
}  // namespace swa::testing

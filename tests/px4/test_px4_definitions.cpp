// SWA's PX4 messages against PX4's own definitions of every supported release (tests/upstream/px4_msgs/<tag>/, PX4's
// .msg files byte for byte, their sources in tests/upstream/README.md): for each release and each message the bridge or
// the stand-in uses, the IDL the bridge picks for that release (swa/px4/release.h) has PX4's fields with PX4's types,
// array sizes and order; the generated type's bytes on the wire are as long as XCDR1 makes PX4's field list, and the
// fields SWA reads sit at the offsets that list gives them; the constants SWA mirrors and the topics' message versions
// are the release's. A new release is a new directory of .msg files and a row in kReleaseDirs: every check then covers
// it.

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <swa/px4/OffboardControlMode_v1_15PubSubTypes.h>
#include <swa/px4/SensorCombined_v1_15PubSubTypes.h>
#include <swa/px4/SensorGps_v1_15PubSubTypes.h>
#include <swa/px4/SensorGps_v1_17PubSubTypes.h>
#include <swa/px4/TrajectorySetpoint_v1_15PubSubTypes.h>
#include <swa/px4/VehicleAttitude_v1_15PubSubTypes.h>
#include <swa/px4/VehicleCommandAck_v1_15PubSubTypes.h>
#include <swa/px4/VehicleCommand_v1_15PubSubTypes.h>
#include <swa/px4/VehicleLocalPosition_v1_15PubSubTypes.h>
#include <swa/px4/VehicleLocalPosition_v1_16PubSubTypes.h>
#include <swa/px4/VehicleOdometry_v1_15PubSubTypes.h>
#include <swa/px4/VehicleStatus_v1_15PubSubTypes.h>
#include <swa/px4/VehicleStatus_v1_16PubSubTypes.h>

#include "swa/px4/release.h"
#include "swa/px4/vehicle.h"
#include "swa/wire/px4.h"

namespace swa::px4::definitions_test {
namespace {

const std::string kMsgDir = std::string(SWA_SOURCE_DIR) + "/tests/upstream/px4_msgs/";
const std::string kIdlDir = std::string(SWA_SOURCE_DIR) + "/idl/px4/";

struct ReleaseDir {
  Release release;
  const char* tag;
};
constexpr ReleaseDir kReleaseDirs[] = {
    {Release::kV1_15, "v1.15.4"}, {Release::kV1_16, "v1.16.0"}, {Release::kV1_17, "v1.17.0"}};

struct Field {
  std::string type;  // PX4's spelling: uint8, float32, bool, ...
  std::string name;
  int array = 0;  // 0: a scalar
  bool operator==(const Field& o) const { return type == o.type && name == o.name && array == o.array; }
};

std::ostream& operator<<(std::ostream& os, const Field& f) {
  return os << f.type << (f.array > 0 ? "[" + std::to_string(f.array) + "]" : "") << " " << f.name;
}

struct MsgDef {
  std::vector<Field> fields;
  std::map<std::string, long long> constants;
};

std::string readText(const std::string& path) {
  std::ifstream in(path);
  EXPECT_TRUE(in) << "cannot read " << path;
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// "float32[4]" -> ("float32", 4).
Field fieldOf(const std::string& type_token, const std::string& name) {
  Field f{type_token, name, 0};
  const std::size_t bracket = type_token.find('[');
  if (bracket != std::string::npos) {
    f.type = type_token.substr(0, bracket);
    f.array = std::stoi(type_token.substr(bracket + 1));
  }
  return f;
}

MsgDef parseMsg(const std::string& path) {
  MsgDef def;
  std::istringstream in(readText(path));
  for (std::string line; std::getline(in, line);) {
    line = line.substr(0, line.find('#'));  // PX4's comments (and its "# TOPICS" lines)
    const std::size_t eq = line.find('=');
    std::istringstream words(line.substr(0, eq));
    std::string type, name;
    words >> type >> name;
    if (type.empty()) continue;
    if (eq == std::string::npos) {
      def.fields.push_back(fieldOf(type, name));
    } else {
      def.constants[name] = std::stoll(line.substr(eq + 1));
    }
  }
  return def;
}

// The members of the one struct in an idl/px4 file, in PX4's type names.
std::vector<Field> parseIdlStruct(const std::string& path) {
  static const std::map<std::string, std::string> kPx4Type = {
      {"boolean", "bool"},  {"int8", "int8"},     {"uint8", "uint8"},   {"int16", "int16"},
      {"uint16", "uint16"}, {"int32", "int32"},   {"uint32", "uint32"}, {"int64", "int64"},
      {"uint64", "uint64"}, {"float", "float32"}, {"double", "float64"}};
  std::vector<Field> fields;
  std::istringstream in(readText(path));
  bool inside = false;
  for (std::string line; std::getline(in, line);) {
    line = line.substr(0, line.find("//"));
    if (line.find("struct ") != std::string::npos) {
      inside = true;
      continue;
    }
    if (!inside) continue;
    if (line.find("};") != std::string::npos) break;
    std::istringstream words(line);
    std::string type, decl;
    if (!(words >> type >> decl)) continue;
    if (!decl.empty() && decl.back() == ';') decl.pop_back();
    const auto t = kPx4Type.find(type);
    EXPECT_NE(t, kPx4Type.end()) << path << ": IDL type '" << type << "' has no PX4 counterpart here";
    Field f = fieldOf(decl, decl);  // "q[4]" -> name q, array 4
    f.name = decl.substr(0, decl.find('['));
    f.type = t == kPx4Type.end() ? type : t->second;
    fields.push_back(f);
  }
  return fields;
}

std::size_t sizeOf(const std::string& px4_type) {
  if (px4_type == "bool" || px4_type == "int8" || px4_type == "uint8") return 1;
  if (px4_type == "int16" || px4_type == "uint16") return 2;
  if (px4_type == "int32" || px4_type == "uint32" || px4_type == "float32") return 4;
  if (px4_type == "int64" || px4_type == "uint64" || px4_type == "float64") return 8;
  ADD_FAILURE() << "no size for " << px4_type;
  return 0;
}

// XCDR1 (classic CDR) of a flat struct of primitives and fixed arrays: each field aligned to its element's size
// (at most 8), counted from the start of the body. Offsets by name, and the body's size.
std::map<std::string, std::size_t> xcdr1Offsets(const std::vector<Field>& fields, std::size_t& size) {
  std::map<std::string, std::size_t> offsets;
  std::size_t at = 0;
  for (const Field& f : fields) {
    const std::size_t s = sizeOf(f.type);
    if (s == 0) continue;
    at = (at + s - 1) / s * s;
    offsets[f.name] = at;
    at += s * static_cast<std::size_t>(f.array > 0 ? f.array : 1);
  }
  size = at;
  return offsets;
}

template <class PubSubType>
std::vector<std::uint8_t> wire(typename PubSubType::type m) {
  PubSubType type;
  eprosima::fastrtps::rtps::SerializedPayload_t p(type.getSerializedSizeProvider(&m)());
  EXPECT_TRUE(type.serialize(&m, &p));
  return std::vector<std::uint8_t>(p.data, p.data + p.length);
}

constexpr std::size_t kEncapsulation = 4;

// What the program uses of one message in a release: the .msg name, the IDL file the bridge takes for the
// release, its topic's base name, and the bytes of a default instance of that generated type.
struct Used {
  std::string msg, idl, topic;
  std::vector<std::uint8_t> bytes;
};

std::vector<Used> usedIn(Release r) {
  const bool new_status = hasV116VehicleStatus(r);
  const bool new_position = hasV116VehicleLocalPosition(r);
  const bool new_gps = hasV117SensorGps(r);
  return {
      {"VehicleAttitude", "VehicleAttitude_v1_15", "vehicle_attitude",
       wire<px4_msgs::msg::VehicleAttitudePubSubType>({})},
      {"VehicleStatus", new_status ? "VehicleStatus_v1_16" : "VehicleStatus_v1_15", "vehicle_status",
       new_status ? wire<px4_v1_16::px4_msgs::msg::VehicleStatusPubSubType>({})
                  : wire<px4_msgs::msg::VehicleStatusPubSubType>({})},
      {"OffboardControlMode", "OffboardControlMode_v1_15", "offboard_control_mode",
       wire<px4_msgs::msg::OffboardControlModePubSubType>({})},
      {"TrajectorySetpoint", "TrajectorySetpoint_v1_15", "trajectory_setpoint",
       wire<px4_msgs::msg::TrajectorySetpointPubSubType>({})},
      {"VehicleCommand", "VehicleCommand_v1_15", "vehicle_command", wire<px4_msgs::msg::VehicleCommandPubSubType>({})},
      {"VehicleCommandAck", "VehicleCommandAck_v1_15", "vehicle_command_ack",
       wire<px4_msgs::msg::VehicleCommandAckPubSubType>({})},
      {"SensorGps", new_gps ? "SensorGps_v1_17" : "SensorGps_v1_15", "vehicle_gps_position",
       new_gps ? wire<px4_v1_17::px4_msgs::msg::SensorGpsPubSubType>({})
               : wire<px4_msgs::msg::SensorGpsPubSubType>({})},
      {"VehicleLocalPosition", new_position ? "VehicleLocalPosition_v1_16" : "VehicleLocalPosition_v1_15",
       "vehicle_local_position",
       new_position ? wire<px4_v1_16::px4_msgs::msg::VehicleLocalPositionPubSubType>({})
                    : wire<px4_msgs::msg::VehicleLocalPositionPubSubType>({})},
      {"VehicleOdometry", "VehicleOdometry_v1_15", "vehicle_visual_odometry",
       wire<px4_msgs::msg::VehicleOdometryPubSubType>({})},
      {"SensorCombined", "SensorCombined_v1_15", "sensor_combined", wire<px4_msgs::msg::SensorCombinedPubSubType>({})},
  };
}

TEST(Px4Definitions, EveryMessageOfEveryReleaseHasPx4sFieldsTypesAndOrderInTheIdlTheBridgePicks) {
  for (const ReleaseDir& rd : kReleaseDirs) {
    for (const Used& u : usedIn(rd.release)) {
      SCOPED_TRACE(std::string(rd.tag) + " " + u.msg + " as " + u.idl + ".idl");
      // GIVEN PX4's definition of the release and SWA's IDL for it
      const MsgDef px4 = parseMsg(kMsgDir + rd.tag + "/" + u.msg + ".msg");
      const std::vector<Field> idl = parseIdlStruct(kIdlDir + u.idl + ".idl");
      // THEN field for field the same (a dropped, added, renamed, retyped or moved field fails)
      ASSERT_FALSE(px4.fields.empty());
      EXPECT_EQ(idl, px4.fields);
      // AND the generated type is as long on the wire as PX4's field list in XCDR1
      std::size_t size = 0;
      xcdr1Offsets(px4.fields, size);
      EXPECT_EQ(u.bytes.size(), kEncapsulation + size);
    }
  }
}

TEST(Px4Definitions, TheFieldsSwaReadsOfVehicleStatusSitWherePx4PutsThemInEveryRelease) {
  for (const ReleaseDir& rd : kReleaseDirs) {
    SCOPED_TRACE(rd.tag);
    // GIVEN the release's VehicleStatus offsets from PX4's definition
    std::size_t size = 0;
    const auto offsets = xcdr1Offsets(parseMsg(kMsgDir + rd.tag + "/VehicleStatus.msg").fields, size);
    // WHEN the stand-in's status is serialised in the layout the release takes
    const auto make = [](auto tag) {
      using Status = decltype(tag);
      return wire::vehicleStatus<Status>(0x0102030405060708ULL, kArmingStateArmed, kNavStateOffboard, true, 7);
    };
    const std::vector<std::uint8_t> b =
        hasV116VehicleStatus(rd.release)
            ? wire<px4_v1_16::px4_msgs::msg::VehicleStatusPubSubType>(make(px4_v1_16::px4_msgs::msg::VehicleStatus{}))
            : wire<px4_msgs::msg::VehicleStatusPubSubType>(make(px4_msgs::msg::VehicleStatus{}));
    ASSERT_EQ(b.size(), kEncapsulation + size);
    // THEN arming_state, nav_state, failsafe, system_id and the last field are at PX4's offsets
    const auto byteAt = [&](const char* name) { return b.at(kEncapsulation + offsets.at(name)); };
    EXPECT_EQ(byteAt("arming_state"), kArmingStateArmed);
    EXPECT_EQ(byteAt("nav_state"), kNavStateOffboard);
    EXPECT_EQ(byteAt("failsafe"), 1);
    EXPECT_EQ(byteAt("system_id"), 7);
    EXPECT_EQ(byteAt("pre_flight_checks_pass"), 1);
    std::uint64_t timestamp = 0;
    std::memcpy(&timestamp, b.data() + kEncapsulation + offsets.at("timestamp"), sizeof timestamp);
    EXPECT_EQ(timestamp, 0x0102030405060708ULL);
  }
}

TEST(Px4Definitions, MirroredConstantsAndTopicVersionsAreEveryReleases) {
  const std::vector<std::string> messages = {
      "VehicleAttitude",   "VehicleStatus", "OffboardControlMode",  "TrajectorySetpoint", "VehicleCommand",
      "VehicleCommandAck", "SensorGps",     "VehicleLocalPosition", "VehicleOdometry",    "SensorCombined"};
  const std::map<std::string, std::string> topic = {{"VehicleAttitude", "vehicle_attitude"},
                                                    {"VehicleStatus", "vehicle_status"},
                                                    {"OffboardControlMode", "offboard_control_mode"},
                                                    {"TrajectorySetpoint", "trajectory_setpoint"},
                                                    {"VehicleCommand", "vehicle_command"},
                                                    {"VehicleCommandAck", "vehicle_command_ack"},
                                                    {"SensorGps", "vehicle_gps_position"},
                                                    {"VehicleLocalPosition", "vehicle_local_position"},
                                                    {"VehicleOdometry", "vehicle_visual_odometry"},
                                                    {"SensorCombined", "sensor_combined"}};
  for (const ReleaseDir& rd : kReleaseDirs) {
    SCOPED_TRACE(rd.tag);
    // GIVEN the release's definitions
    const MsgDef status = parseMsg(kMsgDir + rd.tag + "/VehicleStatus.msg");
    const MsgDef command = parseMsg(kMsgDir + rd.tag + "/VehicleCommand.msg");
    // THEN the vehicle constants SWA mirrors are the release's
    EXPECT_EQ(status.constants.at("ARMING_STATE_DISARMED"), kArmingStateDisarmed);
    EXPECT_EQ(status.constants.at("ARMING_STATE_ARMED"), kArmingStateArmed);
    EXPECT_EQ(status.constants.at("NAVIGATION_STATE_ALTCTL"), kNavStateAltctl);
    EXPECT_EQ(status.constants.at("NAVIGATION_STATE_POSCTL"), kNavStatePosctl);
    EXPECT_EQ(status.constants.at("NAVIGATION_STATE_AUTO_LOITER"), kNavStateAutoLoiter);
    EXPECT_EQ(status.constants.at("NAVIGATION_STATE_OFFBOARD"), kNavStateOffboard);
    EXPECT_EQ(command.constants.at("VEHICLE_CMD_DO_SET_MODE"), kCmdDoSetMode);
    EXPECT_EQ(command.constants.at("VEHICLE_CMD_COMPONENT_ARM_DISARM"), kCmdComponentArmDisarm);
    // AND each message's topic carries the release's MESSAGE_VERSION (absent: 0) as the release names it
    for (const std::string& m : messages) {
      const MsgDef def = parseMsg(kMsgDir + rd.tag + "/" + m + ".msg");
      const auto v = def.constants.find("MESSAGE_VERSION");
      const long long version = v == def.constants.end() ? 0 : v->second;
      EXPECT_EQ(messageVersion(rd.release, topic.at(m)), version) << m;
      EXPECT_EQ(topicName(rd.release, topic.at(m)),
                version > 0 ? topic.at(m) + "_v" + std::to_string(version) : topic.at(m))
          << m;
    }
  }
}

TEST(Px4Release, ParsesItsNamesAndPatchReleasesAndRefusesOthers) {
  EXPECT_EQ(parseRelease("v1.15"), Release::kV1_15);
  EXPECT_EQ(parseRelease("1.16"), Release::kV1_16);
  EXPECT_EQ(parseRelease("v1.17.0"), Release::kV1_17);
  EXPECT_EQ(parseRelease("1.16.12"), Release::kV1_16);
  for (const char* bad : {"", "v", "1.14", "v1.18", "1.1", "1.15.", "1.15.x", "1.150", "v1.17rc1", "V1.17"}) {
    EXPECT_FALSE(parseRelease(bad)) << bad;
  }
  for (const Release r : kReleases) EXPECT_EQ(parseRelease(releaseName(r)), r);
  EXPECT_EQ(releaseList(), "v1.15, v1.16, v1.17");
  EXPECT_EQ(kNewestRelease, Release::kV1_17);
}

}  // namespace
}  // namespace swa::px4::definitions_test

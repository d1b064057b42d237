// The foreign ROS 2 types SWA speaks (idl/ros/*.idl: std_msgs, builtin_interfaces, geometry_msgs, sensor_msgs,
// vision_msgs, UVDAR's mrs_msgs, ArduPilot's ardupilot_msgs) against their upstream definitions, kept byte for byte in
// tests/upstream/ with their repository, path and commit (tests/upstream/README.md): every IDL struct has an upstream
// .msg (or half of a .srv) with the same fields, types, array sizes and order, and every upstream file kept there is
// spoken by some IDL struct. A field we typed wrong (UVDAR's uint32 id, issue #42) fails here, whatever we believe.
// PX4's messages of every release are held against tests/upstream/px4_msgs by tests/px4/test_px4_definitions.cpp.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "msg_lockstep.h"

namespace swa::testing::lockstep {
namespace {

namespace fs = std::filesystem;

const fs::path kIdlDir = fs::path(SWA_SOURCE_DIR) / "idl" / "ros";
const fs::path kUpstreamDir = fs::path(SWA_SOURCE_DIR) / "tests" / "upstream";

bool isPrimitive(const std::string& element) {
  static const std::set<std::string> kPrimitives = {"bool",   "byte",  "char",   "float32", "float64",
                                                    "int8",   "uint8", "int16",  "uint16",  "int32",
                                                    "uint32", "int64", "uint64", "string",  "wstring"};
  return kPrimitives.count(element) != 0;
}

// A field type with every message type qualified by its package: "Point[]" in geometry_msgs is
// "geometry_msgs/Point[]".
std::string qualified(const std::string& type, const std::string& package) {
  const std::size_t bracket = type.find('[');
  const std::string element = type.substr(0, bracket);
  const std::string array = bracket == std::string::npos ? "" : type.substr(bracket);
  if (isPrimitive(element) || element.find('/') != std::string::npos) return type;
  return package + "/" + element + array;
}

// Keyed "pkg/Name" (a service's halves "pkg/Name_Request" and "pkg/Name_Response"), every type qualified; the
// constants are dropped (they are not on the wire, and SWA's IDL of a foreign type does not mirror them).
struct Definitions {
  Messages messages;
  std::vector<std::string> problems;
  void add(const std::string& package, const std::string& name, const std::string& text) {
    Message m;
    for (const std::string& p : parseMsg(package + "/" + name, text, m)) problems.push_back(p);
    m.package = package;
    m.constants.clear();
    for (Field& f : m.fields) f.type = qualified(f.type, package);
    messages[package + "/" + name] = m;
  }
};

Definitions upstream() {
  Definitions d;
  for (const auto& package : fs::directory_iterator(kUpstreamDir)) {
    if (!package.is_directory() || package.path().filename() == "px4_msgs") continue;
    const std::string pkg = package.path().filename().string();
    for (const auto& kind : fs::directory_iterator(package.path())) {
      for (const auto& file : fs::directory_iterator(kind.path())) {
        const std::string name = file.path().stem().string();
        const std::string text = readFile(file.path());
        if (file.path().extension() == ".msg") {
          d.add(pkg, name, text);
        } else if (file.path().extension() == ".srv") {  // request --- response
          const std::size_t split = text.find("\n---");
          if (split == std::string::npos) {
            d.problems.push_back(file.path().string() + ": no '---' between request and response");
            continue;
          }
          d.add(pkg, name + "_Request", text.substr(0, split + 1));
          d.add(pkg, name + "_Response", text.substr(text.find('\n', split + 1) + 1));
        } else {
          d.problems.push_back(file.path().string() + ": neither .msg nor .srv");
        }
      }
    }
  }
  return d;
}

Definitions ours() {
  Definitions d;
  for (const auto& entry : fs::directory_iterator(kIdlDir)) {
    if (entry.path().extension() != ".idl") continue;
    Messages file;
    for (const std::string& p : parseIdl(entry.path().stem().string(), readFile(entry.path()), file)) {
      d.problems.push_back(p);
    }
    for (auto& [name, m] : file) {
      for (Field& f : m.fields) f.type = qualified(f.type, m.package);
      d.messages[m.package + "/" + name] = m;
    }
  }
  return d;
}

TEST(ForeignDefinitions, EveryForeignTypeOfOursHasUpstreamsFieldsTypesAndOrder) {
  // GIVEN SWA's IDL of the foreign types and the upstream definitions, both read without a problem
  const Definitions idl = ours();
  const Definitions up = upstream();
  ASSERT_TRUE(idl.problems.empty()) << lines(idl.problems);
  ASSERT_TRUE(up.problems.empty()) << lines(up.problems);
  // AND every package SWA speaks is there (a reader that read nothing would pass the comparison)
  for (const char* name :
       {"std_msgs/Header", "builtin_interfaces/Time", "geometry_msgs/PoseWithCovariance", "sensor_msgs/Imu",
        "sensor_msgs/NavSatFix", "vision_msgs/Detection3DArray", "mrs_msgs/PoseWithCovarianceIdentified",
        "ardupilot_msgs/Status", "ardupilot_msgs/ModeSwitch_Response", "tf2_msgs/TFMessage"}) {
    ASSERT_EQ(idl.messages.count(name), 1u) << name;
    ASSERT_EQ(up.messages.count(name), 1u) << name;
    EXPECT_FALSE(up.messages.at(name).fields.empty()) << name;
  }
  // THEN each has upstream's fields in upstream's order, and no upstream file kept is left unchecked
  const std::vector<std::string> problems = compare(idl.messages, up.messages);
  EXPECT_TRUE(problems.empty()) << lines(problems);
}

TEST(ForeignDefinitions, TheComparisonFindsAWrongWidthAMovedFieldAndAMissingType) {
  // GIVEN upstream's definitions, which match
  const Definitions idl = ours();
  const Definitions up = upstream();
  ASSERT_TRUE(compare(idl.messages, up.messages).empty());

  // WHEN UVDAR's id is 32 bits wide, as SWA once had it THEN it is found
  Messages narrow = idl.messages;
  narrow.at("mrs_msgs/PoseWithCovarianceIdentified").fields.at(0).type = "uint32";
  const std::vector<std::string> width = compare(narrow, up.messages);
  ASSERT_EQ(width.size(), 1u) << lines(width);
  EXPECT_NE(width[0].find("'uint64 id'"), std::string::npos) << width[0];

  // WHEN two fields of the IMU trade places THEN both places are found
  Messages moved = idl.messages;
  auto& imu = moved.at("sensor_msgs/Imu").fields;
  std::swap(imu.at(1), imu.at(3));
  EXPECT_EQ(compare(moved, up.messages).size(), 2u);

  // WHEN an IDL struct has no upstream file, or an upstream file no IDL struct THEN each is found
  Messages missing = idl.messages;
  missing.erase("geometry_msgs/Twist");
  missing["geometry_msgs/Accel"] = Message{};
  EXPECT_EQ(compare(missing, up.messages).size(), 2u) << lines(compare(missing, up.messages));
}

TEST(ForeignDefinitions, TheMsgReaderTakesUpstreamsDefaultValuesAndServices) {
  // GIVEN ROS 2 .msg text with a constant, a default value and a bare type of the same package
  Definitions d;
  d.add("sensor_msgs", "NavSatStatus",
        "int8 STATUS_UNKNOWN = -2  # not yet set\nint8 status -2 # STATUS_UNKNOWN\n"
        "uint16 service\n");
  d.add("geometry_msgs", "Pose", "Point position\nQuaternion orientation\n");
  // THEN the default is not a field's name, the constant no field, and the bare types are qualified
  ASSERT_TRUE(d.problems.empty()) << lines(d.problems);
  const auto& status = d.messages.at("sensor_msgs/NavSatStatus").fields;
  ASSERT_EQ(status.size(), 2u);
  EXPECT_EQ(status[0], (Field{"int8", "status"}));
  EXPECT_EQ(d.messages.at("geometry_msgs/Pose").fields.at(0), (Field{"geometry_msgs/Point", "position"}));
  // AND an IDL fixed array and another package's type read as ROS spells them
  Messages idl;
  const auto problems = parseIdl("X", R"(module geometry_msgs { module msg {
    @final struct PoseWithCovariance { geometry_msgs::msg::Pose pose; double covariance[36]; }; }; };)",
                                 idl);
  ASSERT_TRUE(problems.empty()) << lines(problems);
  EXPECT_EQ(idl.at("PoseWithCovariance").package, "geometry_msgs");
  EXPECT_EQ(idl.at("PoseWithCovariance").fields.at(0), (Field{"geometry_msgs/Pose", "pose"}));
  EXPECT_EQ(idl.at("PoseWithCovariance").fields.at(1), (Field{"float64[36]", "covariance"}));
}

}  // namespace
}  // namespace swa::testing::lockstep

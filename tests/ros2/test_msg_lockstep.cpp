// The ROS 2 interface package (idl/swa_msgs/msg/*.msg) in lock-step with the IDL (idl/*.idl): a ROS user who builds
// swa_msgs decodes exactly what SWA's processes put on the wire in the ros2 naming (msg_lockstep.h has the rules).

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "msg_lockstep.h"

namespace swa::testing::lockstep {
namespace {

namespace fs = std::filesystem;

struct Tree {
  Messages idl, msg;
  std::vector<std::string> problems;
};

Tree readTree() {
  Tree tree;
  const fs::path idl_dir = fs::path(SWA_SOURCE_DIR) / "idl";
  for (const auto& entry : fs::directory_iterator(idl_dir)) {
    if (entry.path().extension() != ".idl") continue;
    for (const std::string& p : parseIdl(entry.path().stem().string(), readFile(entry.path()), tree.idl)) {
      tree.problems.push_back(p);
    }
  }
  for (const auto& entry : fs::directory_iterator(idl_dir / "swa_msgs" / "msg")) {
    if (entry.path().extension() != ".msg") continue;
    const std::string name = entry.path().stem().string();
    for (const std::string& p : parseMsg(name, readFile(entry.path()), tree.msg[name])) tree.problems.push_back(p);
  }
  return tree;
}

TEST(MsgLockstep, EveryIdlStructHasItsMsgFieldForField) {
  // GIVEN the IDL files and the .msg files of the source tree
  const Tree tree = readTree();
  ASSERT_TRUE(tree.problems.empty()) << lines(tree.problems);
  // THEN every message SWA sends is there (a parser that read nothing would pass the comparison)
  for (const char* name : {"MessageHeader", "Imu", "Detection", "Detections", "GnssFix", "VelocitySetpoint",
                           "AgentState", "Clock", "UavTruth", "SwarmTruth", "ScenarioEvent", "SwarmMetrics"}) {
    ASSERT_EQ(tree.idl.count(name), 1u) << name;
    EXPECT_FALSE(tree.idl.at(name).fields.empty()) << name;
  }
  EXPECT_EQ(tree.idl.at("AgentState").fields.size(), 30u);
  EXPECT_EQ(tree.idl.at("AgentState").constants.size(), 7u);
  // AND the .msg files say exactly what the IDL says
  const std::vector<std::string> problems = compare(tree.idl, tree.msg);
  EXPECT_TRUE(problems.empty()) << lines(problems);
}

TEST(MsgLockstep, ADivergenceIsFound) {
  // GIVEN the tree's messages
  const Tree tree = readTree();
  ASSERT_TRUE(tree.problems.empty()) << lines(tree.problems);

  // WHEN two fields of a .msg are swapped THEN the comparison names the message and both places
  Messages swapped = tree.msg;
  std::swap(swapped.at("Imu").fields[2], swapped.at("Imu").fields[3]);
  const std::vector<std::string> order = compare(tree.idl, swapped);
  ASSERT_EQ(order.size(), 2u) << lines(order);
  EXPECT_NE(order[0].find("Imu: field 3 is 'float64 pitch_rad'"), std::string::npos) << order[0];

  // WHEN a field's width differs (float32 is not the IDL's double) THEN it is found
  Messages narrow = tree.msg;
  narrow.at("GnssFix").fields[3].type = "float32";
  EXPECT_EQ(compare(tree.idl, narrow).size(), 1u);

  // WHEN an enum value or a constant is missing or wrong THEN it is found
  Messages constants = tree.msg;
  Message& state = constants.at("AgentState");
  state.constants.erase(state.constants.find(Constant{"uint32", "STAGE_NO_INPUT", "3"}));
  Message& detections = constants.at("Detections");
  detections.constants.erase(detections.constants.begin());
  detections.constants.insert({"int32", "ANONYMOUS_ID", "0"});
  EXPECT_EQ(compare(tree.idl, constants).size(), 2u) << lines(compare(tree.idl, constants));

  // WHEN a .msg is missing, or one has no IDL struct THEN both are found
  Messages extra = tree.msg;
  extra.erase("Clock");
  extra["Stray"] = Message{};
  EXPECT_EQ(compare(tree.idl, extra).size(), 2u) << lines(compare(tree.idl, extra));
}

TEST(MsgLockstep, TheParsersReadSequencesEnumsAndConstants) {
  // GIVEN an IDL file with every construct SWA uses, and its .msg
  Messages idl;
  const auto idl_problems = parseIdl("Thing", R"(#include "MessageHeader.idl"
    module swa { module msg {
    const int32 NONE = -1;  // a constant
    enum Colour { RED, /* comment */ GREEN };
    @final
    struct Thing { MessageHeader header; Colour colour; sequence<int32, 8> ids; sequence<Part> parts; double x_m; };
    }; };)",
                                     idl);
  Message msg;
  const auto msg_problems = parseMsg("Thing", R"(int32 NONE=-1
uint32 RED=0  # trailing comment
uint32 GREEN = 1
MessageHeader header
uint32 colour
int32[<=8] ids
Part[] parts
float64 x_m
)",
                                     msg);
  // THEN both read the same message
  ASSERT_TRUE(idl_problems.empty()) << lines(idl_problems);
  ASSERT_TRUE(msg_problems.empty()) << lines(msg_problems);
  ASSERT_EQ(idl.at("Thing").fields.size(), 5u);
  EXPECT_EQ(idl.at("Thing").fields[2].type, "int32[<=8]");
  EXPECT_EQ(idl.at("Thing").fields[3].type, "Part[]");
  EXPECT_TRUE(compare(idl, Messages{{"Thing", msg}}).empty()) << lines(compare(idl, Messages{{"Thing", msg}}));
}

}  // namespace
}  // namespace swa::testing::lockstep

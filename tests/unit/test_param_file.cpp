// Issue #11: parameter files are bounded before they are parsed (devices, size, binary garbage, thousands of keys)
// and a list of problems stays one screen long.

#include <unistd.h>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "scratch.h"
#include "swa/agent/config_io.h"
#include "swa/params/file.h"

namespace swa::agent {
namespace {

namespace fs = std::filesystem;

class ParamFile : public ::testing::Test {
 protected:
  fs::path write(const std::string& name, const std::string& text) { return dir_.write(name, text); }
  swa::testing::ScratchDir dir_{"swa_param_file"};
};

std::string problemOf(const std::string& path) {
  std::string problem;
  EXPECT_FALSE(params::readTextFile(path, "configuration", problem).has_value()) << path;
  return problem;
}

TEST_F(ParamFile, DevicesArePlainErrorsNotHangsOrGigabytes) {
  // Before issue #11: --scenario /dev/zero grew to 6 GB, --config /dev/urandom hung.
  EXPECT_EQ(problemOf("/dev/zero"), "is a device, pipe or socket, not a configuration file");
  EXPECT_EQ(problemOf("/dev/urandom"), "is a device, pipe or socket, not a configuration file");
  // A hang would meet the test's timeout; how fast it returns is BM_RefuseDevice's bar in bench_agent_core
  EXPECT_THROW(loadAgentConfig("/dev/urandom"), ConfigError);
}

TEST_F(ParamFile, SizeIsCappedAtOneMebibyte) {
  const fs::path at_limit = write("at.yaml", "# " + std::string(params::kMaxFileBytes - 3, 'x') + "\n");
  std::string problem;
  EXPECT_TRUE(params::readTextFile(at_limit.string(), "configuration", problem).has_value()) << problem;
  const fs::path over = write("over.yaml", std::string(params::kMaxFileBytes + 1, '#'));
  EXPECT_EQ(problemOf(over.string()), "is 1048577 bytes; a configuration file may have at most 1048576 (1 MiB)");
}

TEST_F(ParamFile, BinaryGarbageIsNotText) {
  const fs::path bin = write("bin.yaml", std::string("mode: swa\n\0\x01\x02", 13));
  EXPECT_EQ(problemOf(bin.string()), "is not a text file (it contains NUL bytes)");
  EXPECT_EQ(problemOf((dir_ / "missing.yaml").string()), "configuration file does not exist");
  EXPECT_EQ(problemOf(dir_.string()), "is a directory, not a configuration file");
}

TEST_F(ParamFile, ThousandsOfKeysAreRefusedUpFront) {
  // GIVEN a 0.8 MB file of 45000 unknown keys (before: 16 s of spelling suggestions, then 45000 lines)
  std::string text;
  for (int i = 0; i < 45000; ++i) text += "bogus_key_" + std::to_string(i) + ": 1\n";
  const fs::path many = write("many.yaml", text);
  try {
    loadAgentConfig(many.string());
    FAIL() << "accepted";
  } catch (const ConfigError& e) {
    // THEN one problem, at once
    ASSERT_EQ(e.problems().size(), 1u);
    EXPECT_EQ(e.problems()[0], "has more than 2000 keys: not a configuration file");
  }
  // How fast the refusal is (it was 16 s) is a timing, so its bar is in bench_agent_core (BM_RefuseManyKeys)
}

TEST(ParamProblems, RepeatsAreMergedLongOnesCutAndTheListCapped) {
  std::vector<std::string> problems(1000, "formation.k = 0 is out of range [1, 16]");
  problems.push_back("x = '" + std::string(5000, 'a') + "' is not valid");
  for (int i = 0; i < 40; ++i) problems.push_back("unknown key 'k" + std::to_string(i) + "'");
  const std::vector<std::string> s = params::summariseProblems(problems);
  ASSERT_EQ(s.size(), params::kMaxProblems + 1);
  EXPECT_EQ(s[0], "formation.k = 0 is out of range [1, 16] (1000 times)");
  EXPECT_EQ(s[1].size(), params::kMaxProblemChars);
  EXPECT_EQ(s[1].substr(s[1].size() - 3), "...");
  EXPECT_EQ(s.back(), "... and 22 more distinct problems");
  // AND ConfigError applies it: its message is a screenful
  const ConfigError e("f.yaml", problems);
  EXPECT_EQ(e.problems().size(), params::kMaxProblems + 1);
  EXPECT_LT(std::string(e.what()).size(), 8000u);
}

}  // namespace
}  // namespace swa::agent

// A program's --out (swa/app/run_directory.h): what an earlier run wrote is removed, nothing else (issue #30:
// a reused --out kept the old run's files beside the new one's).

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <stdexcept>
#include <string>

#include "swa/app/run_directory.h"

namespace swa::app {
namespace {

namespace fs = std::filesystem;

class RunDirectory : public ::testing::Test {
 protected:
  void SetUp() override {
    const std::string test = ::testing::UnitTest::GetInstance()->current_test_info()->name();
    dir_ = fs::temp_directory_path() / ("swa_run_directory_" + std::to_string(::getpid()) + "_" + test);
    fs::remove_all(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  static void touch(const fs::path& p) {
    fs::create_directories(p.parent_path());
    std::ofstream(p) << "x";
  }
  fs::path dir_;
};

TEST_F(RunDirectory, ANewDirectoryOrOneWithoutMarkerIsLeftAsItIs) {
  EXPECT_NO_THROW(claimRunDirectory(dir_));
  EXPECT_FALSE(fs::exists(dir_));
  touch(dir_ / "notes.txt");
  touch(dir_ / "logs" / "agent_0.log");
  EXPECT_NO_THROW(claimRunDirectory(dir_));
  EXPECT_TRUE(fs::exists(dir_ / "notes.txt"));
  EXPECT_TRUE(fs::exists(dir_ / "logs" / "agent_0.log"));
  // AND a file given as --out is refused
  EXPECT_THROW(claimRunDirectory(dir_ / "notes.txt"), std::runtime_error);
}

TEST_F(RunDirectory, WhatAnEarlierRunWroteIsRemovedAndNothingElse) {
  // GIVEN a directory where the user's shell put a log before a --compare launch wrote two runs and a combine log
  touch(dir_ / "launch.log");
  const std::set<std::string> before = entriesOf(dir_);
  touch(dir_ / "swa" / "summary.json");
  touch(dir_ / "standalone" / "logs" / "sim.log");
  touch(dir_ / "combine.log");
  markRunDirectory(dir_, before);
  // AND a file the user added after the run
  touch(dir_ / "notes.txt");
  // WHEN the next launch claims it
  claimRunDirectory(dir_);
  // THEN nothing of the old run is left, and the user's files are
  EXPECT_EQ(entriesOf(dir_), (std::set<std::string>{"launch.log", "notes.txt"}));
}

TEST_F(RunDirectory, AMarkerNamingPathsOutsideTheDirectoryRemovesNothingThere) {
  // GIVEN a marker edited to name the parent, an absolute path and a path below
  touch(dir_ / "keep" / "file.txt");
  touch(dir_ / "sub" / "file.txt");
  std::ofstream(dir_ / kRunMarker) << "..\n/\nsub/file.txt\n.\n";
  // WHEN it is claimed THEN only the marker goes
  claimRunDirectory(dir_);
  EXPECT_TRUE(fs::exists(dir_ / "keep" / "file.txt"));
  EXPECT_TRUE(fs::exists(dir_ / "sub" / "file.txt"));
  EXPECT_FALSE(fs::exists(dir_ / kRunMarker));
}

}  // namespace
}  // namespace swa::app

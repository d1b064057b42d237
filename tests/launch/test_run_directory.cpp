// swa_launch's --out (deploy/launch/run_directory.h): an earlier run's directory is emptied, anything else refused
// untouched (issue #30: a reused --out kept the old run's files beside the new one's).

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "run_directory.h"

namespace swa::launch {
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

TEST_F(RunDirectory, ANewOrEmptyDirectoryIsTakenAsItIs) {
  EXPECT_NO_THROW(claimRunDirectory(dir_));
  EXPECT_FALSE(fs::exists(dir_));
  fs::create_directories(dir_);
  EXPECT_NO_THROW(claimRunDirectory(dir_));
  EXPECT_TRUE(fs::is_empty(dir_));
}

TEST_F(RunDirectory, AnEarlierRunIsRemovedWhole) {
  // GIVEN the directory of an earlier launch with --compare: its marker, two runs and the comparison's log
  fs::create_directories(dir_);
  markRunDirectory(dir_);
  touch(dir_ / "swa" / "summary.json");
  touch(dir_ / "standalone" / "logs" / "sim.log");
  touch(dir_ / "combine.log");
  // WHEN it is claimed again THEN nothing of the old run is left
  claimRunDirectory(dir_);
  EXPECT_TRUE(fs::is_empty(dir_));
}

TEST_F(RunDirectory, ARunOfAnOlderVersionWithoutTheMarkerIsRecognisedByItsFiles) {
  touch(dir_ / "logs" / "agent_0.log");
  touch(dir_ / "scenario.yaml");
  touch(dir_ / "report.html");
  claimRunDirectory(dir_);
  EXPECT_TRUE(fs::is_empty(dir_));
}

TEST_F(RunDirectory, AnythingElseIsRefusedAndLeftAsItWas) {
  // GIVEN a directory with a file of the user's, and one with a logs/ folder but nothing else of a run
  touch(dir_ / "notes.txt");
  touch(dir_ / "logs" / "mine.log");
  // WHEN it is claimed THEN it is refused, saying why, and both files are still there
  try {
    claimRunDirectory(dir_);
    FAIL() << "claimed a directory swa_launch did not write";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("is not empty and holds no earlier swa_launch run"), std::string::npos)
        << e.what();
  }
  EXPECT_TRUE(fs::exists(dir_ / "notes.txt"));
  EXPECT_TRUE(fs::exists(dir_ / "logs" / "mine.log"));
  // AND a file given as --out is refused too
  EXPECT_THROW(claimRunDirectory(dir_ / "notes.txt"), std::runtime_error);
}

}  // namespace
}  // namespace swa::launch

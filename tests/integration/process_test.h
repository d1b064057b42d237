#pragma once
// What GoogleTest tests that run the SWA processes share beyond process_support.h: a fresh directory for a test's
// files, and the fixture of a run of swa_sim and swa_agent processes.

#include <gtest/gtest.h>
#include <unistd.h>

#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "private_shm.h"
#include "process_support.h"
#include "scratch.h"

namespace swa::testing {

// A new, empty directory for a test's files: <temp>/<prefix>_<pid>, and _<test name> after that when `per_test` (so
// that the directories failed tests keep are told apart).
inline fs::path freshTestDir(const std::string& prefix, bool per_test = false) {
  std::string name = prefix + "_" + std::to_string(::getpid());
  if (per_test) name += "_" + testNameForFiles();
  const fs::path dir = fs::temp_directory_path() / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// A run of swa_sim and swa_agent processes on a DDS domain of the test's, with its files in dir_. Tear-down stops the
// simulator, then the agents (each SIGTERM, then SIGKILL), then what the test observed the run with
// (stopObservers), removes the shared-memory files of killed processes, and the directory unless a check failed.
class ProcessRun : public ::testing::Test {
 protected:
  void TearDown() override {
    sim_.reset();
    agents_.clear();
    stopObservers();
    const std::vector<std::string> removed = janitor_.clean();
    if (!removed.empty()) std::cerr << "removed " << removed.size() << " abandoned /dev/shm file(s)\n";
    if (!HasFailure()) fs::remove_all(dir_);
  }

  // Ends the test's own participants.
  virtual void stopObservers() = 0;

  OwnShm own_shm_;      // first member: this test's /dev/shm is its own (private_shm.h)
  ShmJanitor janitor_;  // sees /dev/shm before anything of ours exists
  fs::path dir_;
  int domain_ = 0;
  std::vector<std::unique_ptr<Child>> agents_;
  std::unique_ptr<Child> sim_;
};

}  // namespace swa::testing

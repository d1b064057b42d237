#pragma once
// Shared by the tests that write files: a directory or a file of the test's own under the system's temporary
// directory, named after the process and the test (ctest runs each test in its own process, two at a time), and
// removed with everything in it when it goes out of scope, also when an assertion ended the test early.

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>

namespace swa::testing {

// The running test's name as one file name: a parameterised test's "Name/0" would otherwise be a folder.
inline std::string testNameForFiles() {
  const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
  std::string name = info != nullptr ? info->name() : "none";
  for (char& c : name) {
    if (c == '/') c = '_';
  }
  return name;
}

// "<prefix>_<pid>_<test name>_<n>": no two alive at once in one process, none shared between processes.
inline std::filesystem::path scratchPath(const std::string& prefix, const std::string& suffix = "") {
  static int counter = 0;
  return std::filesystem::temp_directory_path() / (prefix + "_" + std::to_string(::getpid()) + "_" +
                                                   testNameForFiles() + "_" + std::to_string(counter++) + suffix);
}

class ScratchDir {
 public:
  explicit ScratchDir(const std::string& prefix) : path_(scratchPath(prefix)) {
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~ScratchDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;

  const std::filesystem::path& path() const { return path_; }
  std::string string() const { return path_.string(); }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }
  // Writes `text` (as bytes) into the file `name` of the directory and returns its path.
  std::filesystem::path write(const std::string& name, const std::string& text) const {
    const std::filesystem::path p = path_ / name;
    std::ofstream(p, std::ios::binary) << text;
    return p;
  }

 private:
  std::filesystem::path path_;
};

// A file holding `text`, e.g. a scenario or a parameter file for a loader under test.
class ScratchFile {
 public:
  explicit ScratchFile(const std::string& text, const std::string& suffix = ".yaml")
      : path_(scratchPath("swa_test", suffix).string()) {
    std::ofstream(path_, std::ios::binary) << text;
  }
  ~ScratchFile() {
    std::error_code ec;
    std::filesystem::remove(path_, ec);
  }
  ScratchFile(const ScratchFile&) = delete;
  ScratchFile& operator=(const ScratchFile&) = delete;
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

}  // namespace swa::testing

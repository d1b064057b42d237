#pragma once

#include <stdexcept>
#include <string>
#include <vector>

namespace swa::params {

// All problems found in one parameter source (a file path, "<string>" or "--set"). what() lists them one per line,
// each prefixed by the source: "agent.yaml: control.k_p = -1 is out of range [0, 20] 1/s (line 6, column 8)".
class ConfigError : public std::runtime_error {
 public:
  // Repeated problems are merged, long ones cut and at most 20 listed (file.h): a broken 10 MB file is one screen
  // of errors, not five million lines.
  ConfigError(std::string source, std::vector<std::string> problems);

  const std::string& source() const noexcept { return source_; }
  // One message per problem, without the source prefix. Each names the offending key.
  const std::vector<std::string>& problems() const noexcept { return problems_; }

 private:
  struct Summarised {};
  ConfigError(Summarised, std::string source, std::vector<std::string> problems);

  std::string source_;
  std::vector<std::string> problems_;
};

}  // namespace swa::params

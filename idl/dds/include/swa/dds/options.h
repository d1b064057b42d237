#pragma once
// Command-line and environment plumbing shared by the DDS nodes (no DDS include: testable on its own).

#include <optional>
#include <string>
#include <vector>

namespace swa::dds {

// Highest usable domain id: Fast DDS maps domain d to UDP ports 7400 + 250 d + ..., which must stay below 65536.
constexpr int kMaxDomainId = 232;

// Parses a whole string as an integer / finite real in [min, max]; nullopt on anything else (trailing garbage,
// overflow, empty).
std::optional<long long> parseInteger(const std::string& text, long long min, long long max);
std::optional<double> parseReal(const std::string& text, double min, double max);

// The domain id: `cli_value` (--domain) if given, else the environment variable SWA_DOMAIN, else 0.
// Throws std::invalid_argument naming the source when the value is not an integer in [0, kMaxDomainId].
int resolveDomain(const std::optional<std::string>& cli_value);

// The XML profiles file: the environment variable SWA_DDS_PROFILES if set and non-empty, else the repository's
// deploy/dds/profiles.xml (path compiled in). Existence is checked by the Participant.
std::string resolveProfilesFile();

// Walks command-line arguments given as "--key value" or "--key=value". value() consumes the value of the current
// key and records "<key> needs a value" in `problems` when there is none, so parsers report every problem at once.
class ArgWalker {
 public:
  ArgWalker(const std::vector<std::string>& args, std::vector<std::string>& problems)
      : args_(args), problems_(problems) {}
  bool next();                            // advances to the next argument; false at the end
  const std::string& key() const { return key_; }
  const std::string& raw() const { return args_[index_]; }  // the argument as given, e.g. "--x=1"
  std::optional<std::string> value();

 private:
  const std::vector<std::string>& args_;
  std::vector<std::string>& problems_;
  std::size_t index_ = 0;
  std::size_t next_ = 0;
  std::string key_;
  std::optional<std::string> inline_value_;
};

}  // namespace swa::dds

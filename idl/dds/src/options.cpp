#include "swa/dds/options.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <utility>

#ifndef SWA_DEFAULT_PROFILES_FILE
#error "SWA_DEFAULT_PROFILES_FILE must be defined by the build"
#endif

namespace swa::dds {

std::optional<long long> parseInteger(const std::string& text, long long min, long long max) {
  if (text.empty() || std::isspace(static_cast<unsigned char>(text.front()))) return std::nullopt;
  errno = 0;
  char* end = nullptr;
  const long long value = std::strtoll(text.c_str(), &end, 10);
  if (errno != 0 || end != text.c_str() + text.size() || value < min || value > max) return std::nullopt;
  return value;
}

std::optional<double> parseReal(const std::string& text, double min, double max) {
  if (text.empty() || std::isspace(static_cast<unsigned char>(text.front()))) return std::nullopt;
  errno = 0;
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (errno != 0 || end != text.c_str() + text.size() || !std::isfinite(value) || value < min || value > max) {
    return std::nullopt;
  }
  return value;
}

int resolveDomain(const std::optional<std::string>& cli_value) {
  std::string source = "--domain";
  std::string text;
  if (cli_value) {
    text = *cli_value;
  } else if (const char* env = std::getenv("SWA_DOMAIN"); env != nullptr && *env != '\0') {
    source = "SWA_DOMAIN";
    text = env;
  } else {
    return 0;
  }
  const auto value = parseInteger(text, 0, kMaxDomainId);
  if (!value) {
    throw std::invalid_argument(source + " = '" + text + "' is not a DDS domain id (an integer in [0, " +
                                std::to_string(kMaxDomainId) + "])");
  }
  return static_cast<int>(*value);
}

std::string resolveProfilesFile() {
  if (const char* env = std::getenv("SWA_DDS_PROFILES"); env != nullptr && *env != '\0') return env;
  return SWA_DEFAULT_PROFILES_FILE;
}

bool ArgWalker::next() {
  if (next_ >= args_.size()) return false;
  index_ = next_++;
  key_ = args_[index_];
  inline_value_.reset();
  if (const auto eq = key_.find('='); key_.rfind("--", 0) == 0 && eq != std::string::npos) {
    inline_value_ = key_.substr(eq + 1);
    key_ = key_.substr(0, eq);
  }
  return true;
}

std::optional<std::string> ArgWalker::value() {
  if (inline_value_) return std::exchange(inline_value_, std::nullopt);
  if (next_ < args_.size()) return args_[next_++];
  problems_.push_back(key_ + " needs a value");
  return std::nullopt;
}

}  // namespace swa::dds

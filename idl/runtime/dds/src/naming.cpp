#include "swa/dds/naming.h"

#include <utility>
#include <vector>

#include "name_table.h"

namespace swa::dds {
namespace {

constexpr std::pair<Naming, const char*> kNamingNames[] = {{Naming::kSwa, "swa"}, {Naming::kRos2, "ros2"}};

constexpr const char* kSwaRoot = "swa/";
constexpr const char* kRosTopicPrefix = "rt/";
constexpr const char* kSwaTypeModule = "swa::msg::";
constexpr const char* kRosSwaTypeModule = "swa_msgs::msg::dds_::";
// idl/px4: a release's own layout of a PX4 message lives in an outer module px4_v<major>_<minor>.
constexpr const char* kPx4ReleaseModule = "px4_v";
constexpr const char* kPx4TypeModule = "px4_msgs::";

bool startsWith(const std::string& s, const std::string& prefix) { return s.rfind(prefix, 0) == 0; }

bool isAlpha(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z'); }
bool isDigit(char c) { return c >= '0' && c <= '9'; }

// ROS 2 name tokens (design article "Topic and Service name mapping to DDS"): alphanumerics and '_', not starting with
// a digit, no repeated '_' anywhere.
std::optional<std::string> tokenProblem(const std::string& token) {
  if (token.empty()) return "has an empty token ('//' or a trailing '/')";
  if (isDigit(token[0])) return "has a token starting with a digit ('" + token + "')";
  for (std::size_t k = 0; k < token.size(); ++k) {
    const char c = token[k];
    if (!isAlpha(c) && !isDigit(c) && c != '_') return "has a character other than letters, digits, '_' and '/'";
    if (c == '_' && k + 1 < token.size() && token[k + 1] == '_') return "has a repeated '_'";
  }
  return std::nullopt;
}

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  while (true) {
    const std::size_t at = s.find(sep, start);
    parts.push_back(s.substr(start, at == std::string::npos ? std::string::npos : at - start));
    if (at == std::string::npos) return parts;
    start = at + 1;
  }
}

std::string rosPrefix(const WireNames& names) {
  return names.ros_namespace.empty() ? kRosTopicPrefix : kRosTopicPrefix + names.ros_namespace + "/";
}

}  // namespace

const char* namingName(Naming n) { return detail::nameIn(kNamingNames, n); }

std::optional<Naming> parseNaming(const std::string& name) { return detail::valueIn(kNamingNames, name); }

std::optional<std::string> rosNamespaceProblem(const std::string& ns) {
  const std::string body = startsWith(ns, "/") ? ns.substr(1) : ns;
  if (body.empty()) return "'" + ns + "' is empty";
  if (body.size() > 128) return "'" + ns.substr(0, 40) + "...' is longer than 128 characters";
  for (const std::string& token : split(body, '/')) {
    if (const auto problem = tokenProblem(token)) return "'" + ns + "' " + *problem;
  }
  return std::nullopt;
}

std::string normalRosNamespace(const std::string& ns) { return startsWith(ns, "/") ? ns.substr(1) : ns; }

bool isSwaTopic(const std::string& topic) { return startsWith(topic, kSwaRoot); }

std::string ddsTopic(const WireNames& names, const std::string& topic) {
  if (names.naming == Naming::kSwa || !isSwaTopic(topic)) return topic;
  return rosPrefix(names) + topic;
}

std::optional<std::string> swaTopic(const WireNames& names, const std::string& dds_topic) {
  std::string rest = dds_topic;
  if (names.naming == Naming::kRos2) {
    const std::string prefix = rosPrefix(names);
    if (!startsWith(dds_topic, prefix)) return std::nullopt;
    rest = dds_topic.substr(prefix.size());
  }
  if (!isSwaTopic(rest)) return std::nullopt;
  return rest;
}

std::string ddsType(const WireNames& names, const std::string& generated_type) {
  if (startsWith(generated_type, kPx4ReleaseModule)) {
    const std::size_t at = generated_type.find("::");
    if (at != std::string::npos && startsWith(generated_type.substr(at + 2), kPx4TypeModule)) {
      return generated_type.substr(at + 2);
    }
  }
  if (names.naming == Naming::kSwa || !startsWith(generated_type, kSwaTypeModule)) return generated_type;
  return kRosSwaTypeModule + generated_type.substr(std::string(kSwaTypeModule).size()) + "_";
}

std::optional<std::string> rosTopicOf(const std::string& dds_topic) {
  if (!startsWith(dds_topic, kRosTopicPrefix)) return std::nullopt;
  return "/" + dds_topic.substr(std::string(kRosTopicPrefix).size());
}

bool isValidRosTopic(const std::string& name) {
  if (!startsWith(name, "/") || name.size() < 2) return false;
  for (const std::string& token : split(name.substr(1), '/')) {
    if (tokenProblem(token)) return false;
  }
  return true;
}

std::optional<std::string> rosTypeOf(const std::string& dds_type) {
  // pkg::msg::dds_::Name_ : a package token, "msg", "dds_", a CamelCase name with the trailing '_'.
  const std::vector<std::string> parts = split(dds_type, ':');
  // "a::b" splits into a, "", b: the separators must be exactly "::".
  if (parts.size() != 7 || !parts[1].empty() || !parts[3].empty() || !parts[5].empty()) return std::nullopt;
  const std::string& pkg = parts[0];
  const std::string& name = parts[6];
  if (parts[2] != "msg" || parts[4] != "dds_") return std::nullopt;
  if (pkg.empty() || !(pkg[0] >= 'a' && pkg[0] <= 'z') || tokenProblem(pkg)) return std::nullopt;
  for (const char c : pkg) {
    if (c >= 'A' && c <= 'Z') return std::nullopt;
  }
  if (name.size() < 2 || name.back() != '_' || !(name[0] >= 'A' && name[0] <= 'Z')) return std::nullopt;
  const std::string base = name.substr(0, name.size() - 1);
  for (const char c : base) {
    if (!isAlpha(c) && !isDigit(c)) return std::nullopt;
  }
  return pkg + "/msg/" + base;
}

}  // namespace swa::dds

#include "swa/msg_defs/ros_definition.h"

#include <algorithm>
#include <set>
#include <stdexcept>

#include "msg_texts.h"

namespace swa::msg_defs {
namespace {

const std::set<std::string_view>& primitives() {
  static const std::set<std::string_view> names = {"bool",   "byte",  "char",   "float32", "float64",
                                                   "int8",   "uint8", "int16",  "uint16",  "int32",
                                                   "uint32", "int64", "uint64", "string",  "wstring"};
  return names;
}

// The type of a field line ("Detection[] items  # ..." -> "Detection"), empty for a comment or blank line.
std::string_view fieldType(std::string_view line) {
  const std::size_t start = line.find_first_not_of(" \t");
  if (start == std::string_view::npos || line[start] == '#') return {};
  std::string_view type = line.substr(start, line.find_first_of(" \t", start) - start);
  type = type.substr(0, type.find('['));                // arrays: T[], T[3], T[<=3]
  if (type.rfind("string<=", 0) == 0) return "string";  // bounded strings
  if (type.rfind("wstring<=", 0) == 0) return "wstring";
  return type;
}

std::vector<std::string_view> lines(std::string_view text) {
  std::vector<std::string_view> out;
  while (!text.empty()) {
    const std::size_t end = text.find('\n');
    out.push_back(text.substr(0, end));
    if (end == std::string_view::npos) break;
    text.remove_prefix(end + 1);
  }
  return out;
}

// Every swa_msgs type `type` uses, depth first, each once, not `type` itself.
void collect(std::string_view type, std::vector<std::string_view>& order, std::set<std::string_view>& seen) {
  const std::optional<std::string_view> text = msgText(type);
  for (const std::string_view line : lines(*text)) {
    const std::string_view field = fieldType(line);
    if (field.empty() || primitives().count(field) > 0) continue;
    if (!msgText(field)) {
      throw std::logic_error(std::string(kPackage) + "/" + std::string(type) + " uses " + std::string(field) +
                             ", which is neither a ROS primitive nor a message of " + kPackage);
    }
    if (!seen.insert(field).second) continue;
    order.push_back(field);
    collect(field, order, seen);
  }
}

}  // namespace

std::vector<std::string> typeNames() {
  std::vector<std::string> names;
  for (const detail::MsgText& m : detail::msgTexts()) names.emplace_back(m.name);
  std::sort(names.begin(), names.end());
  return names;
}

std::optional<std::string_view> msgText(std::string_view type) {
  for (const detail::MsgText& m : detail::msgTexts()) {
    if (m.name == type) return m.text;
  }
  return std::nullopt;
}

std::string rosTypeName(std::string_view type) { return std::string(kPackage) + "/msg/" + std::string(type); }

std::optional<std::string> rosDefinition(std::string_view type) {
  const std::optional<std::string_view> text = msgText(type);
  if (!text) return std::nullopt;
  std::vector<std::string_view> order;
  std::set<std::string_view> seen{type};
  collect(type, order, seen);
  std::string out(*text);
  for (const std::string_view dependency : order) {
    if (!out.empty() && out.back() != '\n') out += '\n';
    out += std::string(80, '=') + "\nMSG: " + kPackage + "/" + std::string(dependency) + "\n";
    out += *msgText(dependency);
  }
  return out;
}

}  // namespace swa::msg_defs

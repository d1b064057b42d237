#include "swa/agent/param_yaml.h"

#include "swa/agent/param_text.h"

namespace swa::agent::param {

const char* nodeKindName(const YAML::Node& node) {
  if (node.IsMap()) return "a map";
  if (node.IsSequence()) return "a sequence";
  if (node.IsNull()) return "nothing";
  return "a scalar";
}

bool isQuoted(const YAML::Node& scalar) { return scalar.Tag() == "!" || scalar.Tag() == "tag:yaml.org,2002:str"; }

std::string locationOf(const YAML::Node& node) {
  const YAML::Mark mark = node.Mark();
  if (mark.is_null()) return {};
  return " (line " + std::to_string(mark.line + 1) + ", column " + std::to_string(mark.column + 1) + ")";
}

std::string describeYamlException(const YAML::Exception& e) {
  std::string message = "invalid YAML";
  if (!e.mark.is_null()) {
    message += " at line " + std::to_string(e.mark.line + 1) + ", column " + std::to_string(e.mark.column + 1);
  }
  return message + ": " + e.msg;
}

std::optional<std::string> readNumber(const YAML::Node& value, const std::string& name, const std::string& expected,
                                      double& number) {
  if (!value.IsScalar()) return name + " must be " + expected + ", got " + nodeKindName(value);
  const std::string& text = value.Scalar();
  if (isQuoted(value)) return name + " = \"" + text + "\" is a string; expected " + expected;
  switch (parseNumber(text, number)) {
    case NumberStatus::kNotANumber:
      return name + " = '" + text + "' is not a number; expected " + expected;
    case NumberStatus::kUnrepresentable:
      return name + " = " + text + " cannot be represented as a double";
    case NumberStatus::kOk:
      break;
  }
  return std::nullopt;
}

std::size_t countKeys(const YAML::Node& node, std::size_t limit) {
  std::size_t n = 0;
  if (node.IsMap()) {
    for (const auto& entry : node) {
      if (++n > limit) return n;
      n += countKeys(entry.second, limit - n);
      if (n > limit) return n;
    }
  } else if (node.IsSequence()) {
    for (const auto& item : node) {
      n += countKeys(item, limit - n);
      if (n > limit) return n;
    }
  }
  return n;
}

}  // namespace swa::agent::param

#include "yaml_error.h"

#include <vector>

namespace swa::params::detail {

TextPosition unclosedFlowOpener(const std::string& text, int line, int column) {
  std::vector<TextPosition> open;
  int l = 1, c = 0;
  char quote = '\0';
  bool comment = false;
  char previous = '\n';
  for (const char ch : text) {
    ++c;
    if (l > line || (l == line && c >= column)) break;
    if (ch == '\n') {
      ++l;
      c = 0;
      comment = false;
      if (quote == '\'') quote = '\0';  // a stray single quote ends with its line; YAML would say so itself
      previous = ch;
      continue;
    }
    if (comment) continue;
    if (quote != '\0') {
      if (ch == quote && !(quote == '"' && previous == '\\')) quote = '\0';
    } else if (ch == '#' && (previous == ' ' || previous == '\t' || previous == '\n' || c == 1)) {
      comment = true;
    } else if (ch == '"' || ch == '\'') {
      quote = ch;
    } else if (ch == '[' || ch == '{') {
      open.push_back({l, c, ch});
    } else if ((ch == ']' || ch == '}') && !open.empty()) {
      open.pop_back();
    }
    previous = ch;
  }
  return open.empty() ? TextPosition{} : open.back();
}

std::string yamlErrorText(const YAML::Exception& e, const std::string& text) {
  std::string out = "invalid YAML";
  if (e.mark.is_null()) return out + ": " + e.msg;
  out += " at line " + std::to_string(e.mark.line + 1) + ", column " + std::to_string(e.mark.column + 1) + ": " + e.msg;
  if (e.msg.find("flow not found") != std::string::npos) {
    const TextPosition at = unclosedFlowOpener(text, e.mark.line + 1, e.mark.column + 1);
    if (at.line > 0) {
      out += " (the '" + std::string(1, at.opener) + "' at line " + std::to_string(at.line) + ", column " +
             std::to_string(at.column) + " is never closed)";
    }
  }
  return out;
}

}  // namespace swa::params::detail

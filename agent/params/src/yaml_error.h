#pragma once
// The text of a YAML syntax error for a person: where yaml-cpp stopped, and, for an unclosed flow sequence or map,
// where it was opened. yaml-cpp reports an unclosed '[' or '{' where it gave up, which is the next key's line or the
// end of the file, one or more lines after the mistake.

#include <string>

#include <yaml-cpp/exceptions.h>

namespace swa::params::detail {

std::string yamlErrorText(const YAML::Exception& e, const std::string& text);

// The line and column (from 1) of the last '[' or '{' in `text` before `line`:`column` (from 1) that is not closed
// before it, skipping quoted strings and comments; or {0, 0} if there is none.
struct TextPosition {
  int line = 0, column = 0;
  char opener = '\0';
};
TextPosition unclosedFlowOpener(const std::string& text, int line, int column);

}  // namespace swa::params::detail

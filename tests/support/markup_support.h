#pragma once
// Shared by the tests of text output (CSV, JSON, SVG plots, report.html, study.html): counting a part of a text, and
// finding elements and reading their attributes and texts in the SVG and HTML the monitor and the studies write.

#include <cstddef>
#include <string>
#include <vector>

namespace swa::monitor::testing {

// How often `part` occurs in `text` (overlapping occurrences count).
inline int occurrences(const std::string& text, const std::string& part) {
  int n = 0;
  for (std::size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++n;
  return n;
}

// The start tags of every element `<name ...>` in `markup` carrying class="cls" (a class attribute of exactly that
// value).
inline std::vector<std::string> elements(const std::string& markup, const std::string& name, const std::string& cls) {
  std::vector<std::string> out;
  const std::string open = "<" + name + " ";
  for (std::size_t pos = markup.find(open); pos != std::string::npos; pos = markup.find(open, pos + 1)) {
    const std::string tag = markup.substr(pos, markup.find('>', pos) - pos + 1);
    if (tag.find("class=\"" + cls + "\"") != std::string::npos) out.push_back(tag);
  }
  return out;
}

// The value of attribute `name` in a start tag; "" when the tag has none.
inline std::string attr(const std::string& tag, const std::string& name) {
  const std::string key = " " + name + "=\"";
  const std::size_t pos = tag.find(key);
  if (pos == std::string::npos) return "";
  const std::size_t begin = pos + key.size();
  return tag.substr(begin, tag.find('"', begin) - begin);
}

// A numeric attribute (std::invalid_argument when the tag has none).
inline double num(const std::string& tag, const std::string& name) { return std::stod(attr(tag, name)); }

// The text content of each <text class="cls"> element in `markup`, in document order.
inline std::vector<std::string> texts(const std::string& markup, const std::string& cls) {
  std::vector<std::string> out;
  const std::string open = "<text class=\"" + cls + "\"";
  for (std::size_t at = markup.find(open); at != std::string::npos; at = markup.find(open, at + 1)) {
    const std::size_t begin = markup.find('>', at) + 1;
    out.push_back(markup.substr(begin, markup.find("</text>", begin) - begin));
  }
  return out;
}

}  // namespace swa::monitor::testing

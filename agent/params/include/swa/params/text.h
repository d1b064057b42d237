#pragma once
// Numbers, ranges, key suggestions and layout as the parameter engine writes them, so every parameter file and
// every message reads alike. Locale-independent; no yaml-cpp.

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace swa::params {

struct Range {
  double min;
  double max;
  bool min_open;
  bool max_open;
};
constexpr Range closed(double lo, double hi) { return {lo, hi, false, false}; }     // [lo, hi]
constexpr Range openClosed(double lo, double hi) { return {lo, hi, true, false}; }  // (lo, hi]
constexpr Range closedOpen(double lo, double hi) { return {lo, hi, false, true}; }  // [lo, hi)
constexpr Range open(double lo, double hi) { return {lo, hi, true, true}; }         // (lo, hi)

bool inRange(const Range& r, double v);
// "[lo, hi]", "(lo, hi]", ...: the bounds as integers if `integral`, else as formatNumber.
std::string formatRange(const Range& r, bool integral);

// Why `v` (shown to the user as `shown`) is not a valid value of the numeric parameter `name`, if it is not: not
// finite, not an integer (if `integral`), or outside `range`, which the message calls `range_text`.
std::optional<std::string> numberProblem(const std::string& name, double v, const std::string& shown, bool integral,
                                         const Range& range, const std::string& range_text);

enum class NumberStatus { kOk, kNotANumber, kUnrepresentable };
// A YAML plain scalar as a number: decimal/scientific notation, .inf/-.inf/.nan spellings.
NumberStatus parseNumber(const std::string& text, double& value);

// Shortest text that reads back as exactly `v` ("inf", "nan" as std::to_chars writes them).
std::string formatNumber(double v);
// As formatNumber, with infinities and NaN in YAML's spelling (".inf", "-.inf", ".nan").
std::string formatYamlNumber(double v);
// A real as YAML: exact round trip and always recognisably a float (YAML 1.1 readers such as PyYAML need a '.' in
// the mantissa).
std::string formatYamlReal(double v);

std::string join(const std::vector<std::string>& items, const std::string& separator);
bool startsWith(const std::string& text, std::string_view prefix);

// The candidate nearest to `key` within an edit distance of 2 (optimal string alignment, case-insensitive; the
// first of equally near ones), or "".
std::string closestMatch(const std::string& key, const std::vector<std::string>& candidates);
// The only candidate whose last dotted component equals that of `key` ("focal.radius_m" -> "formation.radius_m"),
// or "" if there is none or more than one.
std::string sameLeafMatch(const std::string& key, const std::vector<std::string>& candidates);
// " (did you mean 'suggestion'?)", or "" if `suggestion` is empty.
std::string didYouMean(const std::string& suggestion);

// Rows as columns padded to the widest cell plus two spaces, the first row (the header) underlined with dashes.
std::string formatTable(const std::vector<std::vector<std::string>>& rows);

struct CommentedLine {
  std::string text;
  std::string comment;  // empty = none
};
// One line each, the "# comment"s aligned two spaces after the longest commented text.
std::string alignComments(const std::vector<CommentedLine>& lines);

}  // namespace swa::params

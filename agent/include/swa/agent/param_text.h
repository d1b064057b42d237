#pragma once

// Internal: text helpers shared by the parameter loaders, the agent's (agent/src/config_io.cpp) and the
// simulator's (sim/src/scenario_io.cpp), so that both read numbers, describe ranges and word their messages
// alike. Not part of the agent's API. No yaml-cpp here: the helpers that need it are in param_yaml.h.

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace swa::agent::param {

// ------------------------------------------------------------------------------------------------------------
// Ranges of numeric parameters.

struct Range {
  double min;
  double max;
  bool min_open;
  bool max_open;
};
constexpr Range closed(double lo, double hi) { return {lo, hi, false, false}; }      // [lo, hi]
constexpr Range openClosed(double lo, double hi) { return {lo, hi, true, false}; }   // (lo, hi]
constexpr Range closedOpen(double lo, double hi) { return {lo, hi, false, true}; }   // [lo, hi)
constexpr Range open(double lo, double hi) { return {lo, hi, true, true}; }          // (lo, hi)

bool inRange(const Range& r, double v);

// "[lo, hi]", "(lo, hi]", ...: the bounds as integers if `integral`, else as formatNumber.
std::string formatRange(const Range& r, bool integral);

// Why `v` (shown to the user as `shown`) is not a valid value of the numeric parameter `name`, if it is not:
// not finite, not an integer (if `integral`), or outside `range`, which the message calls `range_text`
// (e.g. "[1, 16]" or "(0, 100] m").
std::optional<std::string> numberProblem(const std::string& name, double v, const std::string& shown, bool integral,
                                         const Range& range, const std::string& range_text);

// ------------------------------------------------------------------------------------------------------------
// Numbers as text (locale-independent).

enum class NumberStatus { kOk, kNotANumber, kUnrepresentable };

// A YAML plain scalar as a number: decimal/scientific notation, .inf/-.inf/.nan spellings.
NumberStatus parseNumber(const std::string& text, double& value);

// Shortest text that reads back as exactly `v`; infinities and NaN as std::to_chars writes them ("inf", "nan").
std::string formatNumber(double v);

// As formatNumber, but infinities and NaN in YAML's spelling (".inf", "-.inf", ".nan").
std::string formatYamlNumber(double v);

// A real as YAML: exact round trip, and always recognisably a float (YAML 1.1 readers such as PyYAML need a
// '.' in the mantissa and a signed exponent); infinities and NaN as ".inf", "-.inf", ".nan".
std::string formatYamlReal(double v);

// ------------------------------------------------------------------------------------------------------------
// Strings and keys.

std::string join(const std::vector<std::string>& items, const std::string& separator);

bool startsWith(const std::string& text, std::string_view prefix);

// Optimal-string-alignment distance (Levenshtein plus adjacent transpositions), case-insensitive.
std::size_t editDistance(const std::string& a, const std::string& b);

// The candidate nearest to `key` within an edit distance of 2 (the first of equally near ones), or "".
std::string closestMatch(const std::string& key, const std::vector<std::string>& candidates);

// The only candidate whose last dotted component equals that of `key` ("focal.radius_m" -> "formation.radius_m"),
// or "" if there is none or more than one.
std::string sameLeafMatch(const std::string& key, const std::vector<std::string>& candidates);

// " (did you mean 'suggestion'?)", or "" if `suggestion` is empty.
std::string didYouMean(const std::string& suggestion);

// "unknown key 'key'", followed by didYouMean(suggestion).
std::string unknownKeyMessage(const std::string& key, const std::string& suggestion);

// ------------------------------------------------------------------------------------------------------------
// Layout.

// Rows as columns padded to the widest cell plus two spaces, one row a line, the first row (the header)
// underlined with dashes.
std::string formatTable(const std::vector<std::vector<std::string>>& rows);

struct CommentedLine {
  std::string text;
  std::string comment;  // empty = none
};

// One line each, the "# comment"s aligned two spaces after the longest commented text.
std::string alignComments(const std::vector<CommentedLine>& lines);

}  // namespace swa::agent::param

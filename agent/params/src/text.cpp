#include "swa/params/text.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <limits>
#include <system_error>

namespace swa::params {

bool inRange(const Range& r, double v) {
  const bool above_min = r.min_open ? v > r.min : v >= r.min;
  const bool below_max = r.max_open ? v < r.max : v <= r.max;
  return above_min && below_max;
}

std::string formatRange(const Range& r, bool integral) {
  const auto bound = [&](double v) { return integral ? std::to_string(static_cast<long long>(v)) : formatNumber(v); };
  return std::string(r.min_open ? "(" : "[") + bound(r.min) + ", " + bound(r.max) + (r.max_open ? ")" : "]");
}

std::optional<std::string> numberProblem(const std::string& name, double v, const std::string& shown, bool integral,
                                         const Range& range, const std::string& range_text) {
  if (!std::isfinite(v)) return name + " = " + shown + " is not a finite number";
  if (integral && std::trunc(v) != v) return name + " = " + shown + " is not an integer";
  if (!inRange(range, v)) return name + " = " + shown + " is out of range " + range_text;
  return std::nullopt;
}

NumberStatus parseNumber(const std::string& text, double& value) {
  if (text == ".nan" || text == ".NaN" || text == ".NAN") {
    value = std::numeric_limits<double>::quiet_NaN();
    return NumberStatus::kOk;
  }
  for (const char* inf : {".inf", ".Inf", ".INF"}) {
    if (text == inf || text == std::string("+") + inf) {
      value = std::numeric_limits<double>::infinity();
      return NumberStatus::kOk;
    }
    if (text == std::string("-") + inf) {
      value = -std::numeric_limits<double>::infinity();
      return NumberStatus::kOk;
    }
  }
  std::string_view digits = text;
  if (!digits.empty() && digits.front() == '+') {
    digits.remove_prefix(1);
    if (!digits.empty() && digits.front() == '-') return NumberStatus::kNotANumber;
  }
  if (digits.empty()) return NumberStatus::kNotANumber;
  const char* end = digits.data() + digits.size();
  const auto [ptr, ec] = std::from_chars(digits.data(), end, value);
  if (ptr != end) return NumberStatus::kNotANumber;
  if (ec == std::errc::result_out_of_range) return NumberStatus::kUnrepresentable;
  if (ec != std::errc()) return NumberStatus::kNotANumber;
  return NumberStatus::kOk;
}

std::string formatNumber(double v) {
  std::array<char, 32> buffer{};
  const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), v);
  return std::string(buffer.data(), result.ptr);
}

std::string formatYamlNumber(double v) {
  if (std::isinf(v)) return v > 0 ? ".inf" : "-.inf";
  if (std::isnan(v)) return ".nan";
  return formatNumber(v);
}

std::string formatYamlReal(double v) {
  std::string text = formatYamlNumber(v);
  if (!std::isfinite(v)) return text;
  const auto e = text.find('e');
  const std::string mantissa = text.substr(0, e);
  if (mantissa.find('.') == std::string::npos) text.insert(mantissa.size(), ".0");
  return text;
}

std::string join(const std::vector<std::string>& items, const std::string& separator) {
  std::string out;
  for (std::size_t i = 0; i < items.size(); ++i) {
    if (i > 0) out += separator;
    out += items[i];
  }
  return out;
}

bool startsWith(const std::string& text, std::string_view prefix) {
  return text.size() >= prefix.size() && text.compare(0, prefix.size(), prefix) == 0;
}

namespace {

std::size_t editDistance(const std::string& a, const std::string& b) {
  const auto lower = [](char c) { return static_cast<char>(std::tolower(static_cast<unsigned char>(c))); };
  std::vector<std::vector<std::size_t>> d(a.size() + 1, std::vector<std::size_t>(b.size() + 1));
  for (std::size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
  for (std::size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t cost = lower(a[i - 1]) == lower(b[j - 1]) ? 0 : 1;
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
      if (i > 1 && j > 1 && lower(a[i - 1]) == lower(b[j - 2]) && lower(a[i - 2]) == lower(b[j - 1])) {
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
      }
    }
  }
  return d[a.size()][b.size()];
}

}  // namespace

std::string closestMatch(const std::string& key, const std::vector<std::string>& candidates) {
  std::string best;
  std::size_t best_distance = 3;  // suggest only within an edit distance of 2
  for (const std::string& candidate : candidates) {
    const std::size_t distance = editDistance(key, candidate);
    if (distance < best_distance) {
      best_distance = distance;
      best = candidate;
    }
  }
  return best;
}

std::string sameLeafMatch(const std::string& key, const std::vector<std::string>& candidates) {
  const std::string leaf = key.substr(key.rfind('.') + 1);
  std::vector<std::string> same_leaf;
  for (const std::string& candidate : candidates) {
    if (candidate.substr(candidate.rfind('.') + 1) == leaf) same_leaf.push_back(candidate);
  }
  return same_leaf.size() == 1 ? same_leaf.front() : std::string();
}

std::string didYouMean(const std::string& suggestion) {
  return suggestion.empty() ? std::string() : " (did you mean '" + suggestion + "'?)";
}

std::string formatTable(const std::vector<std::vector<std::string>>& rows) {
  std::vector<std::size_t> width;
  for (const auto& row : rows) {
    if (width.size() < row.size()) width.resize(row.size(), 0);
    for (std::size_t c = 0; c < row.size(); ++c) width[c] = std::max(width[c], row[c].size());
  }
  std::string out;
  for (std::size_t r = 0; r < rows.size(); ++r) {
    std::string line;
    for (std::size_t c = 0; c < rows[r].size(); ++c) {
      line += rows[r][c];
      if (c + 1 < rows[r].size()) line += std::string(width[c] - rows[r][c].size() + 2, ' ');
    }
    out += line + '\n';
    if (r == 0) out += std::string(line.size(), '-') + '\n';
  }
  return out;
}

std::string alignComments(const std::vector<CommentedLine>& lines) {
  std::size_t width = 0;
  for (const CommentedLine& line : lines) {
    if (!line.comment.empty()) width = std::max(width, line.text.size());
  }
  std::string out;
  for (const CommentedLine& line : lines) {
    out += line.text;
    if (!line.comment.empty()) out += std::string(width - line.text.size() + 2, ' ') + "# " + line.comment;
    out += '\n';
  }
  return out;
}

}  // namespace swa::params

#include "study_plan.h"

#include <algorithm>
#include <cctype>
#include <limits>
#include <optional>
#include <set>
#include <stdexcept>

#include "swa/app/number.h"

namespace swa::study {
namespace {

std::vector<std::string> split(const std::string& text, char by) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  while (true) {
    const std::size_t end = text.find(by, start);
    parts.push_back(text.substr(start, end - start));
    if (end == std::string::npos) return parts;
    start = end + 1;
  }
}

// As the parameter engine reads a --set key and value: surrounding spaces are not part of them.
std::string trim(const std::string& text) {
  const auto space = [](char c) { return std::isspace(static_cast<unsigned char>(c)) != 0; };
  const auto begin = std::find_if_not(text.begin(), text.end(), space);
  const auto end = std::find_if_not(text.rbegin(), text.rend(), space).base();
  return begin < end ? std::string(begin, end) : std::string();
}

int positive(const std::string& text, const std::string& what) {
  const std::optional<long long> n = app::parseInteger(text, 1, std::numeric_limits<int>::max());
  if (!n) throw std::invalid_argument(what);
  return static_cast<int>(*n);
}

}  // namespace

Axis makeAxis(std::string key, std::vector<std::string> values, const std::string& what) {
  key = trim(key);
  for (std::string& v : values) v = trim(v);
  if (key.empty()) throw std::invalid_argument(what + " names no key");
  if (values.empty()) throw std::invalid_argument(what + " gives no value");
  std::set<std::string> seen;
  for (const std::string& v : values) {
    if (v.empty()) throw std::invalid_argument(what + " has an empty value");
    if (!seen.insert(v).second) throw std::invalid_argument(what + " gives " + v + " twice");
  }
  return Axis{std::move(key), std::move(values)};
}

Axis parseSweep(const std::string& text) {
  const std::size_t eq = text.find('=');
  const std::string what = "--sweep '" + text + "'";
  if (eq == std::string::npos) throw std::invalid_argument(what + " is not KEY=V1,V2,...");
  return makeAxis(text.substr(0, eq), split(text.substr(eq + 1), ','), what);
}

Shard parseShard(const std::string& text) {
  const std::string bad = "--shard '" + text + "' is not I/N with 1 <= I <= N";
  const std::size_t slash = text.find('/');
  if (slash == std::string::npos) throw std::invalid_argument(bad);
  const Shard s{positive(text.substr(0, slash), bad), positive(text.substr(slash + 1), bad)};
  if (s.index > s.count) throw std::invalid_argument(bad);
  return s;
}

std::vector<std::string> planProblems(const StudyPlan& plan) {
  std::vector<std::string> problems;
  std::set<std::string> keys;
  for (const Axis& a : plan.axes) {
    if (!keys.insert(a.key).second) problems.push_back(a.key + " is swept twice: give its values once");
  }
  if (plan.axes.empty()) problems.push_back("a study sweeps at least one key (--sweep KEY=V1,V2 or study.sweep)");
  // Counted without overflow: eight axes of 256 values would wrap a 64-bit count to 0 runs.
  std::size_t runs = static_cast<std::size_t>(std::max(plan.seeds, 1));
  for (const Axis& a : plan.axes) {
    if (runs > kMaxRuns / std::max<std::size_t>(a.values.size(), 1)) {
      problems.push_back("the study has more than " + std::to_string(kMaxRuns) +
                         " runs (grid points x seeds): cut the sweep");
      break;
    }
    runs *= std::max<std::size_t>(a.values.size(), 1);
  }
  return problems;
}

std::size_t pointCount(const StudyPlan& plan) {
  std::size_t n = 1;
  for (const Axis& a : plan.axes) n *= a.values.size();
  return n;
}

std::size_t runCount(const StudyPlan& plan) { return pointCount(plan) * static_cast<std::size_t>(plan.seeds); }

std::vector<std::string> pointValues(const StudyPlan& plan, std::size_t point) {
  std::vector<std::string> values(plan.axes.size());
  for (std::size_t k = plan.axes.size(); k-- > 0;) {
    const std::vector<std::string>& v = plan.axes[k].values;
    values[k] = v[point % v.size()];
    point /= v.size();
  }
  return values;
}

std::vector<std::string> pointOverrides(const StudyPlan& plan, std::size_t point) {
  const std::vector<std::string> values = pointValues(plan, point);
  std::vector<std::string> overrides;
  for (std::size_t k = 0; k < values.size(); ++k) overrides.push_back(plan.axes[k].key + "=" + values[k]);
  return overrides;
}

std::vector<RunRef> shardRuns(const StudyPlan& plan, const Shard& shard) {
  std::vector<RunRef> runs;
  const auto seeds = static_cast<std::size_t>(plan.seeds);
  for (std::size_t i = static_cast<std::size_t>(shard.index - 1); i < runCount(plan);
       i += static_cast<std::size_t>(shard.count)) {
    runs.push_back({i, i / seeds, static_cast<int>(i % seeds)});
  }
  return runs;
}

}  // namespace swa::study

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

Variant makeVariant(std::string name, std::vector<std::string> overrides, const std::string& what) {
  name = trim(name);
  if (name.empty()) throw std::invalid_argument(what + " names no variant");
  if (overrides.empty()) throw std::invalid_argument(what + " sets nothing");
  std::set<std::string> keys;
  for (std::string& o : overrides) {
    const std::size_t eq = o.find('=');
    if (eq == std::string::npos) throw std::invalid_argument(what + ": '" + o + "' is not KEY=VALUE");
    const std::string key = trim(o.substr(0, eq));
    if (key.empty()) throw std::invalid_argument(what + ": '" + o + "' names no key");
    if (!keys.insert(key).second) throw std::invalid_argument(what + " sets " + key + " twice");
    o = key + "=" + trim(o.substr(eq + 1));
  }
  return Variant{std::move(name), std::move(overrides)};
}

Variant parseVariant(const std::string& text) {
  const std::size_t colon = text.find(':');
  const std::string what = "--variant '" + text + "'";
  if (colon == std::string::npos) throw std::invalid_argument(what + " is not NAME:KEY=V,KEY=V,...");
  return makeVariant(text.substr(0, colon), split(text.substr(colon + 1), ','), what);
}

void setVariants(StudyPlan& plan, std::vector<Variant> variants) {
  plan.axes.erase(
      std::remove_if(plan.axes.begin(), plan.axes.end(), [](const Axis& a) { return a.key == kVariantAxis; }),
      plan.axes.end());
  plan.variants = std::move(variants);
  if (plan.variants.empty()) return;
  Axis axis{kVariantAxis, {}};
  for (const Variant& v : plan.variants) axis.values.push_back(v.name);
  plan.axes.push_back(std::move(axis));
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
  if (plan.axes.empty()) {
    problems.push_back(
        "a study sweeps at least one key or compares variants (--sweep KEY=V1,V2, study.sweep, "
        "--variant NAME:KEY=V or study.variants)");
  }
  std::set<std::string> names;
  for (const Variant& v : plan.variants) {
    if (!names.insert(v.name).second) problems.push_back("variant " + v.name + " is given twice: give it once");
    for (const std::string& o : v.overrides) {
      const std::string key = o.substr(0, o.find('='));
      if (key != kVariantAxis && keys.count(key) > 0) {
        problems.push_back("variant " + v.name + " sets " + key + ", which the study sweeps: set it in one place");
      }
    }
  }
  for (const Axis& a : plan.axes) {
    if (a.key != kVariantAxis) continue;
    for (const std::string& value : a.values) {
      if (names.count(value) == 0) problems.push_back("the variant axis names " + value + ", which no variant defines");
    }
  }
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
  for (std::size_t k = 0; k < values.size(); ++k) {
    if (plan.axes[k].key != kVariantAxis) {
      overrides.push_back(plan.axes[k].key + "=" + values[k]);
      continue;
    }
    for (const Variant& v : plan.variants) {
      if (v.name == values[k]) overrides.insert(overrides.end(), v.overrides.begin(), v.overrides.end());
    }
  }
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

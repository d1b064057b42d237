#include "swa/sim/scenario_io.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <limits>
#include <list>
#include <optional>
#include <set>
#include <sstream>
#include <string_view>
#include <system_error>
#include <type_traits>
#include <utility>

#include "swa/agent/param_file.h"
#include "swa/agent/param_text.h"
#include "swa/agent/param_yaml.h"

namespace swa::sim {

namespace {

using agent::ConfigError;
namespace param = agent::param;
using param::closed;
using param::closedOpen;
using param::describeYamlException;
using param::formatYamlNumber;
using param::formatYamlReal;
using param::isQuoted;
using param::join;
using param::locationOf;
using param::nodeKindName;
using param::openClosed;
using param::Range;
using param::startsWith;

// ------------------------------------------------------------------------------------------------------------
// The parameter table: every scenario field outside `agent` is declared here exactly once. The `agent` section
// is validated by the agent's own table (swa/agent/config_io.h).

enum class Kind { kReal, kInteger, kSeed, kBool, kChoice, kIndexList, kWindowList };

constexpr int kMaxUavs = 256;
constexpr double kMaxTime_s = 1e6;

struct Param {
  std::string key;  // dotted, e.g. "wind.gust_std"; top-level keys have no dot
  Kind kind = Kind::kReal;
  std::string unit;  // empty = dimensionless
  Range range{};     // kReal, kInteger, and each element of kIndexList
  bool allow_infinity = false;       // kReal: +.inf is a valid value (meaning "never")
  std::vector<std::string> choices;  // kChoice only
  std::string meaning;
  std::function<double(const Scenario&)> get_number;
  std::function<void(Scenario&, double)> set_number;
  std::function<std::size_t(const Scenario&)> get_choice;  // choices.size() if the enum holds no listed value
  std::function<void(Scenario&, std::size_t)> set_choice;
  std::function<bool(const Scenario&)> get_bool;
  std::function<void(Scenario&, bool)> set_bool;
  std::function<std::uint64_t(const Scenario&)> get_seed;
  std::function<void(Scenario&, std::uint64_t)> set_seed;
  std::function<std::vector<int>(const Scenario&)> get_list;
  std::function<void(Scenario&, std::vector<int>)> set_list;
  std::function<std::vector<GnssWindow>(const Scenario&)> get_windows;
  std::function<void(Scenario&, std::vector<GnssWindow>)> set_windows;
};

// `access` is a generic lambda `[](auto& s) -> auto& { return s.section.field; }`, usable on const and mutable
// scenarios.
template <class Access>
Param number(std::string key, Access access, std::string unit, Range range, std::string meaning) {
  using Field = std::decay_t<decltype(access(std::declval<Scenario&>()))>;
  static_assert(std::is_arithmetic_v<Field> && !std::is_same_v<Field, bool>);
  Param p;
  p.key = std::move(key);
  p.kind = std::is_integral_v<Field> ? Kind::kInteger : Kind::kReal;
  p.unit = std::move(unit);
  p.range = range;
  p.meaning = std::move(meaning);
  p.get_number = [access](const Scenario& s) { return static_cast<double>(access(s)); };
  p.set_number = [access](Scenario& s, double v) { access(s) = static_cast<Field>(v); };
  return p;
}

template <class Enum, std::size_t N, class Access>
Param choice(std::string key, Access access, const std::array<std::pair<Enum, const char*>, N>& values,
             std::string meaning) {
  Param p;
  p.key = std::move(key);
  p.kind = Kind::kChoice;
  p.meaning = std::move(meaning);
  for (const auto& v : values) p.choices.emplace_back(v.second);
  p.get_choice = [access, values](const Scenario& s) {
    const auto it = std::find_if(values.begin(), values.end(), [&](const auto& v) { return v.first == access(s); });
    return static_cast<std::size_t>(it - values.begin());
  };
  p.set_choice = [access, values](Scenario& s, std::size_t i) { access(s) = values.at(i).first; };
  return p;
}

template <class Access>
Param flag(std::string key, Access access, std::string meaning) {
  Param p;
  p.key = std::move(key);
  p.kind = Kind::kBool;
  p.choices = {"true", "false"};
  p.meaning = std::move(meaning);
  p.get_bool = [access](const Scenario& s) { return access(s); };
  p.set_bool = [access](Scenario& s, bool v) { access(s) = v; };
  return p;
}

template <class Access>
Param seedParam(std::string key, Access access, std::string meaning) {
  Param p;
  p.key = std::move(key);
  p.kind = Kind::kSeed;
  p.meaning = std::move(meaning);
  p.get_seed = [access](const Scenario& s) { return access(s); };
  p.set_seed = [access](Scenario& s, std::uint64_t v) { access(s) = v; };
  return p;
}

template <class Access>
Param indexList(std::string key, Access access, Range element_range, std::string meaning) {
  Param p;
  p.key = std::move(key);
  p.kind = Kind::kIndexList;
  p.range = element_range;
  p.meaning = std::move(meaning);
  p.get_list = [access](const Scenario& s) { return access(s); };
  p.set_list = [access](Scenario& s, std::vector<int> v) { access(s) = std::move(v); };
  return p;
}

template <class Access>
Param windowList(std::string key, Access access, std::string meaning) {
  Param p;
  p.key = std::move(key);
  p.kind = Kind::kWindowList;
  p.unit = "s";
  p.meaning = std::move(meaning);
  p.get_windows = [access](const Scenario& s) { return access(s); };
  p.set_windows = [access](Scenario& s, std::vector<GnssWindow> v) { access(s) = std::move(v); };
  return p;
}

constexpr std::array<std::pair<HeadingMode, const char*>, 2> kHeadings{
    {{HeadingMode::kRandom, "random"}, {HeadingMode::kZero, "zero"}}};
constexpr std::array<std::pair<MpsNoiseModel, const char*>, 2> kNoiseModels{
    {{MpsNoiseModel::kIsotropic, "isotropic"}, {MpsNoiseModel::kRangeBearing, "range_bearing"}}};
constexpr std::array<std::pair<ClockMode, const char*>, 2> kClockModes{
    {{ClockMode::kLockstep, "lockstep"}, {ClockMode::kRealtime, "realtime"}}};

const std::vector<Param>& parameters() {
  static const std::vector<Param> table = {
      number("uav_count", [](auto& s) -> auto& { return s.uav_count; }, "", closed(1, kMaxUavs),
             "number of UAVs in the swarm (indices 0 .. uav_count-1)"),
      seedParam("seed", [](auto& s) -> auto& { return s.seed; },
                "random seed of the world (initial positions, headings, wind, sensor noise)"),
      number("duration_s", [](auto& s) -> auto& { return s.duration_s; }, "s", openClosed(0, 86400),
             "simulated time the run lasts"),

      number("formation.spacing_m", [](auto& s) -> auto& { return s.formation.spacing_m; }, "m",
             openClosed(0, 1000),
             "initial neighbour spacing; also agent.formation.radius_m unless that is given"),
      number("formation.position_jitter_m", [](auto& s) -> auto& { return s.formation.position_jitter_m; }, "m",
             closed(0, 1000), "initial position error around the lattice slots"),

      number("dynamics.rate_hz", [](auto& s) -> auto& { return s.dynamics.rate_hz; }, "Hz", openClosed(0, 10000),
             "simulation step rate; every sensor rate must divide it"),
      number("dynamics.velocity_lag_s", [](auto& s) -> auto& { return s.dynamics.velocity_lag_s; }, "s",
             openClosed(0, 60), "first-order time constant of the velocity response to the command"),
      number("dynamics.speed_limit_mps", [](auto& s) -> auto& { return s.dynamics.speed_limit_mps; }, "m/s",
             openClosed(0, 100), "horizontal speed limit of a UAV"),
      number("dynamics.failsafe_timeout_s", [](auto& s) -> auto& { return s.dynamics.failsafe_timeout_s; }, "s",
             openClosed(0, 60), "a UAV whose commands are older than this brakes to hover"),
      choice("dynamics.heading", [](auto& s) -> auto& { return s.dynamics.heading; }, kHeadings,
             "initial heading of each UAV: random per UAV, or zero (body = world axes)"),
      number("dynamics.heading_rate_std_radps", [](auto& s) -> auto& { return s.dynamics.heading_rate_std_radps; },
             "rad/s", closed(0, 10), "std of a per-UAV constant turn rate (0 = constant heading)"),

      number("wind.gust_std", [](auto& s) -> auto& { return s.wind.gust_std; }, "m/s^2", closed(0, 100),
             "std of the per-UAV Ornstein-Uhlenbeck gust acceleration"),
      number("wind.gust_corr_s", [](auto& s) -> auto& { return s.wind.gust_corr_s; }, "s", openClosed(0, 3600),
             "correlation time of the per-UAV gust"),
      number("wind.common_std", [](auto& s) -> auto& { return s.wind.common_std; }, "m/s^2", closed(0, 100),
             "std of the gust common to every UAV (moves the swarm as a block)"),
      number("wind.common_corr_s", [](auto& s) -> auto& { return s.wind.common_corr_s; }, "s", openClosed(0, 3600),
             "correlation time of the common gust"),

      number("imu.rate_hz", [](auto& s) -> auto& { return s.imu.rate_hz; }, "Hz", openClosed(0, 10000),
             "IMU sample rate; must divide dynamics.rate_hz"),
      number("imu.bias_std", [](auto& s) -> auto& { return s.imu.bias_std; }, "m/s^2", closed(0, 100),
             "std of the constant per-UAV bias of the tilt-derived acceleration"),
      number("imu.noise_std", [](auto& s) -> auto& { return s.imu.noise_std; }, "m/s^2", closed(0, 100),
             "std of the white noise of the tilt-derived acceleration"),
      number("imu.heading_noise_std_rad", [](auto& s) -> auto& { return s.imu.heading_noise_std_rad; }, "rad",
             closed(0, 1), "std of the heading (magnetometer) noise"),

      number("mps.rate_hz", [](auto& s) -> auto& { return s.mps.rate_hz; }, "Hz", openClosed(0, 10000),
             "mutual-perception sensor scan rate; must divide dynamics.rate_hz"),
      number("mps.range_m", [](auto& s) -> auto& { return s.mps.range_m; }, "m", openClosed(0, 10000),
             "neighbours farther than this are not detected"),
      number("mps.fov_deg", [](auto& s) -> auto& { return s.mps.fov_deg; }, "deg", openClosed(0, 360),
             "horizontal field of view, centred on the body x axis"),
      choice("mps.noise_model", [](auto& s) -> auto& { return s.mps.noise_model; }, kNoiseModels,
             "isotropic (noise_var_m2, UVDAR-like) or range_bearing (range_std_m/bearing_std_rad, LiDAR-like)"),
      number("mps.noise_var_m2", [](auto& s) -> auto& { return s.mps.noise_var_m2; }, "m^2", closed(0, 100),
             "isotropic model: variance of each position coordinate (R_o)"),
      number("mps.range_std_m", [](auto& s) -> auto& { return s.mps.range_std_m; }, "m", closed(0, 100),
             "range_bearing model: range noise std"),
      number("mps.bearing_std_rad", [](auto& s) -> auto& { return s.mps.bearing_std_rad; }, "rad", closed(0, 1),
             "range_bearing model: bearing noise std"),
      number("mps.miss_probability", [](auto& s) -> auto& { return s.mps.miss_probability; }, "",
             closedOpen(0, 1), "probability that a neighbour in range is not detected in a scan"),
      number("mps.clutter_rate", [](auto& s) -> auto& { return s.mps.clutter_rate; }, "1/scan", closed(0, 1000),
             "mean number of false detections per scan, uniform in the sensing disc"),
      flag("mps.ids", [](auto& s) -> auto& { return s.mps.ids; },
           "true: detections carry the target's ID (UVDAR-like); false: anonymous (LiDAR-like)"),
      number("mps.latency_s", [](auto& s) -> auto& { return s.mps.latency_s; }, "s", closed(0, 10),
             "delay between a scan and the delivery of its detections"),

      number("gnss.rate_hz", [](auto& s) -> auto& { return s.gnss.rate_hz; }, "Hz", openClosed(0, 10000),
             "GNSS fix rate; must divide dynamics.rate_hz"),
      number("gnss.std_m", [](auto& s) -> auto& { return s.gnss.std_m; }, "m", closed(0, 100),
             "std of each horizontal coordinate of a fix"),
      number("gnss.dropout_start_s", [](auto& s) -> auto& { return s.gnss.dropout_start_s; }, "s",
             closed(0, kMaxTime_s), "every UAV (except keep_uavs) loses GNSS at this time"),
      [] {
        Param p = number("gnss.dropout_end_s", [](auto& s) -> auto& { return s.gnss.dropout_end_s; }, "s",
                         openClosed(0, kMaxTime_s), "GNSS comes back at this time; .inf (default) = never");
        p.allow_infinity = true;
        return p;
      }(),
      indexList("gnss.keep_uavs", [](auto& s) -> auto& { return s.gnss.keep_uavs; }, closed(0, kMaxUavs - 1),
                "UAVs that never lose GNSS, e.g. [0] for one anchored member; indices in [0, uav_count)"),
      windowList("gnss.windows", [](auto& s) -> auto& { return s.gnss.windows; },
                 "extra outages of single UAVs on top of the common one (keep_uavs does not exempt them)"),

      choice("clock.mode", [](auto& s) -> auto& { return s.clock.mode; }, kClockModes,
             "lockstep: deterministic, as fast as the agents answer; realtime: wall-clock pacing"),
      number("clock.speed", [](auto& s) -> auto& { return s.clock.speed; }, "", openClosed(0, 1000),
             "realtime mode: simulated seconds per wall-clock second"),
  };
  return table;
}

const std::vector<std::string>& sectionNames() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> out;
    for (const Param& p : parameters()) {
      const auto dot = p.key.find('.');
      if (dot == std::string::npos) continue;
      std::string section = p.key.substr(0, dot);
      if (std::find(out.begin(), out.end(), section) == out.end()) out.push_back(std::move(section));
    }
    out.emplace_back("agent");
    return out;
  }();
  return names;
}

const Param* findParam(const std::string& key) {
  for (const Param& p : parameters()) {
    if (p.key == key) return &p;
  }
  return nullptr;
}

// The fields of one gnss.windows entry, checked like parameters of their own (messages name them
// "gnss.windows[i].field").
const Param& windowUavParam() {
  static const Param p = [] {
    Param q;
    q.key = "uav";
    q.kind = Kind::kInteger;
    q.range = closed(0, kMaxUavs - 1);
    return q;
  }();
  return p;
}

const Param& windowStartParam() {
  static const Param p = [] {
    Param q;
    q.key = "start_s";
    q.unit = "s";
    q.range = closed(0, kMaxTime_s);
    return q;
  }();
  return p;
}

const Param& windowEndParam() {
  static const Param p = [] {
    Param q;
    q.key = "end_s";
    q.unit = "s";
    q.range = openClosed(0, kMaxTime_s);
    q.allow_infinity = true;
    return q;
  }();
  return p;
}

constexpr std::array<const char*, 3> kWindowFields{"uav", "start_s", "end_s"};
constexpr const char* kWindowExample = "{uav: 3, start_s: 20, end_s: 40}";

// ------------------------------------------------------------------------------------------------------------
// The agent section: its keys are learnt from the agent's own YAML dump, so they never go out of sync.

constexpr std::string_view kAgentPrefix = "agent.";
const char* const kRadiusKey = "agent.formation.radius_m";

struct Shortcut {
  const char* shortcut;
  const char* long_form;
};
constexpr std::array kShortcuts{Shortcut{"agent.k", "agent.formation.k"},
                                Shortcut{"agent.circle_fit", "agent.formation.circle_fit"}};

struct AgentKeys {
  std::vector<std::string> leaves;    // without the "agent." prefix, e.g. "formation.k"
  std::vector<std::string> sections;  // e.g. "formation"
};

void collectAgentKeys(const YAML::Node& map, const std::string& prefix, AgentKeys& keys) {
  for (const auto& entry : map) {
    const std::string key = prefix + entry.first.Scalar();
    if (entry.second.IsMap()) {
      keys.sections.push_back(key);
      collectAgentKeys(entry.second, key + ".", keys);
    } else {
      keys.leaves.push_back(key);
    }
  }
}

const AgentKeys& agentKeys() {
  static const AgentKeys keys = [] {
    AgentKeys k;
    collectAgentKeys(YAML::Load(agent::toYaml(agent::AgentConfig{})), "", k);
    return k;
  }();
  return keys;
}

bool isAgentKey(const std::string& key) { return startsWith(key, kAgentPrefix); }

// A settable key of the scenario (including the agent shortcuts).
bool isLeaf(const std::string& key) {
  if (findParam(key) != nullptr) return true;
  if (!isAgentKey(key)) return false;
  if (std::any_of(kShortcuts.begin(), kShortcuts.end(), [&](const Shortcut& s) { return key == s.shortcut; })) {
    return true;
  }
  const auto& leaves = agentKeys().leaves;
  return std::find(leaves.begin(), leaves.end(), key.substr(kAgentPrefix.size())) != leaves.end();
}

bool isSection(const std::string& key) {
  const auto& names = sectionNames();
  if (std::find(names.begin(), names.end(), key) != names.end()) return true;
  if (!isAgentKey(key)) return false;
  const auto& sections = agentKeys().sections;
  return std::find(sections.begin(), sections.end(), key.substr(kAgentPrefix.size())) != sections.end();
}

// Every settable key, in table order (scenario, then agent long forms, then shortcuts).
std::vector<std::string> allLeaves() {
  std::vector<std::string> out;
  for (const Param& p : parameters()) out.push_back(p.key);
  for (const std::string& leaf : agentKeys().leaves) out.push_back(std::string(kAgentPrefix) + leaf);
  for (const Shortcut& s : kShortcuts) out.emplace_back(s.shortcut);
  return out;
}

std::string canonicalKey(const std::string& key) {
  for (const Shortcut& s : kShortcuts) {
    if (key == s.shortcut) return s.long_form;
  }
  return key;
}

std::optional<std::string> shortcutOf(const std::string& long_form) {
  for (const Shortcut& s : kShortcuts) {
    if (long_form == s.long_form) return std::string(s.shortcut);
  }
  return std::nullopt;
}

// ------------------------------------------------------------------------------------------------------------
// Formatting.

std::string formatList(const std::vector<int>& values) {
  std::vector<std::string> items;
  for (const int v : values) items.push_back(std::to_string(v));
  return "[" + join(items, ", ") + "]";
}

std::string formatWindow(const GnssWindow& w) {
  return "{uav: " + std::to_string(w.uav) + ", start_s: " + formatYamlReal(w.start_s) +
         ", end_s: " + formatYamlReal(w.end_s) + "}";
}

std::string formatWindows(const std::vector<GnssWindow>& windows) {
  std::vector<std::string> items;
  for (const GnssWindow& w : windows) items.push_back(formatWindow(w));
  return "[" + join(items, ", ") + "]";
}

std::string formatRange(const Param& p) {
  switch (p.kind) {
    case Kind::kChoice:
    case Kind::kBool:
      return join(p.choices, "|");
    case Kind::kWindowList:
      return "list of {uav, start_s, end_s}: uav in [0, uav_count), 0 <= start_s < end_s <= " +
             formatYamlNumber(kMaxTime_s) + " or .inf";
    case Kind::kSeed:
      return "[0, " + std::to_string(std::numeric_limits<std::uint64_t>::max()) + "]";
    case Kind::kReal:
    case Kind::kInteger:
    case Kind::kIndexList:
      break;
  }
  std::string text = param::formatRange(p.range, p.kind != Kind::kReal);
  if (p.allow_infinity) text += " or .inf";
  if (p.kind == Kind::kIndexList) text = "list of integers in " + text;
  return text;
}

std::string formatValue(const Param& p, const Scenario& s) {
  switch (p.kind) {
    case Kind::kReal:
      return formatYamlReal(p.get_number(s));
    case Kind::kInteger:
      return std::to_string(static_cast<long long>(p.get_number(s)));
    case Kind::kSeed:
      return std::to_string(p.get_seed(s));
    case Kind::kBool:
      return p.get_bool(s) ? "true" : "false";
    case Kind::kChoice: {
      const std::size_t i = p.get_choice(s);
      return i < p.choices.size() ? p.choices[i] : "<invalid>";
    }
    case Kind::kIndexList:
      return formatList(p.get_list(s));
    case Kind::kWindowList:
      return formatWindows(p.get_windows(s));
  }
  return {};
}

std::string unitSuffix(const Param& p) { return p.unit.empty() ? "" : " " + p.unit; }

const char* typeName(Kind kind) {
  switch (kind) {
    case Kind::kReal:
      return "real";
    case Kind::kInteger:
      return "integer";
    case Kind::kSeed:
      return "uint64";
    case Kind::kBool:
      return "bool";
    case Kind::kChoice:
      return "choice";
    case Kind::kIndexList:
      return "int list";
    case Kind::kWindowList:
      return "window list";
  }
  return "";
}

std::string expectation(const Param& p) {
  switch (p.kind) {
    case Kind::kReal:
      return "a number" + (p.unit.empty() ? std::string() : " in " + p.unit) + " within " + formatRange(p);
    case Kind::kInteger:
      return "an integer within " + formatRange(p);
    case Kind::kSeed:
      return "a non-negative integer (64 bit)";
    case Kind::kBool:
      return "true or false";
    case Kind::kChoice:
      return "one of: " + join(p.choices, ", ");
    case Kind::kIndexList:
      return "a list of UAV indices such as [0] or [] (indices in [0, uav_count))";
    case Kind::kWindowList:
      return std::string("a list of outage windows such as [") + kWindowExample +
             "] or [] (end_s optional: .inf = never restored)";
  }
  return {};
}

// ------------------------------------------------------------------------------------------------------------
// Unknown keys.

std::string unknownKeyMessage(const std::string& key) {
  std::string best;
  // An agent parameter written outside the agent section (e.g. "mode", "focal.tau_s")?
  const std::string in_agent = std::string(kAgentPrefix) + key;
  if (!isAgentKey(key) && (isLeaf(in_agent) || isSection(in_agent))) best = in_agent;

  if (best.empty()) {
    std::vector<std::string> candidates = allLeaves();
    for (const std::string& section : sectionNames()) candidates.push_back(section);
    for (const std::string& section : agentKeys().sections) candidates.push_back(std::string(kAgentPrefix) + section);
    best = param::closestMatch(key, candidates);
  }
  if (best.empty()) best = param::sameLeafMatch(key, allLeaves());  // right name, wrong section (e.g. "imu.gust_std")?
  return param::unknownKeyMessage(key, best);
}

// ------------------------------------------------------------------------------------------------------------
// Problem collection.

class Report {
 public:
  void add(std::string message) { problems_.push_back(std::move(message)); }
  // A problem with the value of parameter `key`: cross-field rules involving it are not checked.
  void addFor(const std::string& key, std::string message) {
    bad_keys_.insert(key);
    add(std::move(message));
  }
  void markBad(const std::string& key) { bad_keys_.insert(key); }
  bool isBad(const std::string& key) const { return bad_keys_.count(key) > 0; }
  bool empty() const { return problems_.empty(); }
  std::vector<std::string> take() { return std::move(problems_); }

 private:
  std::vector<std::string> problems_;
  std::set<std::string> bad_keys_;
};

// One parameter value as given by the file or a --set, before it is checked. Never assigned: assigning a
// YAML::Node writes through to the node it refers to (the document), so entries live in a std::list.
struct Entry {
  std::string key;      // canonical dotted key (shortcuts resolved), e.g. "agent.formation.k"
  std::string written;  // the key as the user wrote it (e.g. "agent.k"); messages use this name
  YAML::Node value;
  std::string where;    // " (line L, column C)", " (from --set k=v)" or ""
  bool from_file = false;

  Entry() = default;
  Entry(const Entry&) = default;
  Entry& operator=(const Entry&) = delete;
};
using Entries = std::list<Entry>;

Entry* findEntry(Entries& entries, const std::string& key) {
  const auto it = std::find_if(entries.begin(), entries.end(), [&](const Entry& e) { return e.key == key; });
  return it == entries.end() ? nullptr : &*it;
}

// Walks a YAML map whose keys live under `prefix` ("" for the top level) into flat entries.
void flatten(const YAML::Node& map, const std::string& prefix, Entries& entries,
             std::set<std::string>& seen, Report& report) {
  for (const auto& item : map) {
    const YAML::Node& key_node = item.first;
    const YAML::Node& value = item.second;
    if (!key_node.IsScalar()) {
      report.add("a key " + (prefix.empty() ? std::string("at the top level") : "under '" + prefix + "'") + " is " +
                 nodeKindName(key_node) + ", not a name" + locationOf(key_node));
      continue;
    }
    const std::string& name = key_node.Scalar();
    const std::string key = prefix.empty() ? name : prefix + "." + name;
    if (!seen.insert(key).second) {
      report.addFor(canonicalKey(key), "duplicate key '" + key + "'" + locationOf(key_node));
      continue;
    }
    if (name.find('.') != std::string::npos) {
      if (isLeaf(key) || isSection(key)) {
        report.add("dotted key '" + key + "' must be written nested (a '" + key.substr(0, key.rfind('.')) +
                   ":' map holding '" + key.substr(key.rfind('.') + 1) + ":'); dotted keys are for --set" +
                   locationOf(key_node));
      } else {
        report.add(unknownKeyMessage(key) + locationOf(key_node));
      }
      continue;
    }
    if (isLeaf(key)) {
      const std::string canonical = canonicalKey(key);
      if (const Entry* other = findEntry(entries, canonical)) {
        const std::string shortcut = shortcutOf(canonical).value_or(key);
        report.addFor(canonical, "'" + key + "' and '" + other->written + "' set the same parameter ('" + shortcut +
                                     "' is a shortcut for '" + canonical + "'); give only one" +
                                     locationOf(key_node));
        continue;
      }
      Entry entry;
      entry.key = canonical;
      entry.written = key;
      entry.value = value;
      entry.where = locationOf(value).empty() ? locationOf(key_node) : locationOf(value);
      entry.from_file = true;
      entries.push_back(std::move(entry));
    } else if (isSection(key)) {
      if (value.IsMap()) {
        flatten(value, key, entries, seen, report);
      } else if (!value.IsNull()) {  // an empty section ("wind:") keeps the defaults
        report.add("'" + key + "' must be a map of parameters, got " + nodeKindName(value) + locationOf(value));
      }
    } else {
      report.add(unknownKeyMessage(key) + locationOf(key_node));
    }
  }
}

std::string trim(const std::string& text) {
  const auto space = [](char c) { return std::isspace(static_cast<unsigned char>(c)) != 0; };
  const auto begin = std::find_if_not(text.begin(), text.end(), space);
  const auto end = std::find_if_not(text.rbegin(), text.rend(), space).base();
  return begin < end ? std::string(begin, end) : std::string();
}

// The --set arguments replace (or add) entries; a later one wins.
void applyOverrides(const std::vector<std::string>& overrides, Entries& entries, Report& report) {
  for (const std::string& text : overrides) {
    const std::string where = " (from --set " + text + ")";
    const auto eq = text.find('=');
    const std::string key = eq == std::string::npos ? std::string() : trim(text.substr(0, eq));
    if (key.empty()) {
      report.add("malformed override '" + text + "'; expected key=value, e.g. --set uav_count=16");
      continue;
    }
    if (!isLeaf(key)) {
      if (isSection(key)) {
        const std::string prefix = key + ".";
        std::string example;
        for (const std::string& leaf : allLeaves()) {
          if (startsWith(leaf, prefix)) {
            example = leaf;
            break;
          }
        }
        report.add("'" + key + "' is a group of parameters, not a parameter; set one of them, e.g. '" + example +
                   "'" + where);
      } else {
        report.add(unknownKeyMessage(key) + where);
      }
      continue;
    }
    const std::string canonical = canonicalKey(key);
    entries.remove_if([&](const Entry& e) { return e.key == canonical; });
    const std::string value_text = text.substr(eq + 1);
    YAML::Node value;
    try {
      value = YAML::Load(value_text);
    } catch (const YAML::Exception& e) {
      report.addFor(canonical, key + " = '" + value_text + "' is not a valid YAML value: " + e.msg + where);
      continue;
    }
    Entry entry;
    entry.key = canonical;
    entry.written = key;
    entry.value = value;
    entry.where = where;
    entries.push_back(std::move(entry));
  }
}

// Why `v` (shown as `shown`) is not a valid value of numeric parameter `p`, if it is not.
std::optional<std::string> numberProblem(const Param& p, double v, const std::string& name, const std::string& shown) {
  if (p.allow_infinity && !std::isfinite(v)) {
    if (v == std::numeric_limits<double>::infinity()) return std::nullopt;
    return name + " = " + shown + " is not a finite number; expected " + expectation(p);
  }
  return param::numberProblem(name, v, shown, p.kind != Kind::kReal, p.range, formatRange(p) + unitSuffix(p));
}

// Reads a plain scalar as a number for parameter `p`; reports and returns nullopt if it is not a valid one.
std::optional<double> readNumber(const Param& p, const YAML::Node& value, const std::string& name,
                                 const std::function<void(std::string)>& fail) {
  double number = 0.0;
  auto problem = param::readNumber(value, name, expectation(p), number);
  if (!problem) problem = numberProblem(p, number, name, value.Scalar());
  if (problem) {
    fail(std::move(*problem));
    return std::nullopt;
  }
  return number;
}

bool isDigits(std::string_view text) {
  return !text.empty() && std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; });
}

void assignSeed(const Param& p, const Entry& e, Scenario& s, const std::function<void(std::string)>& fail) {
  const std::string& text = e.value.Scalar();
  std::string_view digits = text;
  if (!digits.empty() && digits.front() == '+') digits.remove_prefix(1);
  if (!digits.empty() && digits.front() == '-' && isDigits(digits.substr(1))) {
    return fail(p.key + " = " + text + " is out of range " + formatRange(p));
  }
  if (!isDigits(digits)) return fail(p.key + " = '" + text + "' is not " + expectation(p));
  std::uint64_t seed = 0;
  const auto [ptr, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), seed);
  if (ec != std::errc() || ptr != digits.data() + digits.size()) {
    return fail(p.key + " = " + text + " is out of range " + formatRange(p));
  }
  p.set_seed(s, seed);
}

void assignList(const Param& p, const Entry& e, Scenario& s, Report& report) {
  std::vector<int> list;
  bool ok = true;
  std::size_t index = 0;
  for (const YAML::Node& element : e.value) {
    const std::string name = p.key + "[" + std::to_string(index++) + "]";
    const std::string where = e.from_file && !locationOf(element).empty() ? locationOf(element) : e.where;
    const auto fail = [&](std::string message) {
      ok = false;
      report.addFor(p.key, std::move(message) + where);
    };
    Param element_param = p;
    element_param.kind = Kind::kInteger;
    if (const auto v = readNumber(element_param, element, name, fail)) list.push_back(static_cast<int>(*v));
  }
  if (ok) p.set_list(s, std::move(list));
}

// One gnss.windows entry: a map of uav, start_s and (optionally) end_s. Reports every problem; nullopt if any.
std::optional<GnssWindow> readWindow(const YAML::Node& element, const std::string& name,
                                     const std::function<void(std::string, const YAML::Node&)>& fail) {
  if (!element.IsMap()) {
    fail(name + " must be a map such as " + kWindowExample + ", got " + nodeKindName(element), element);
    return std::nullopt;
  }
  bool ok = true;
  std::set<std::string> seen;
  std::optional<double> uav;
  std::optional<double> start_s;
  std::optional<double> end_s;
  std::optional<YAML::Node> end_node;  // copy-constructed only: assigning a YAML::Node writes through
  for (const auto& item : element) {
    const YAML::Node& key_node = item.first;
    const YAML::Node& value = item.second;
    if (!key_node.IsScalar()) {
      ok = false;
      fail("a key in " + name + " is " + nodeKindName(key_node) + ", not a name; expected uav, start_s, end_s",
           key_node);
      continue;
    }
    const std::string& field = key_node.Scalar();
    const std::string field_name = name + "." + field;
    const auto field_fail = [&](std::string message) {
      ok = false;
      fail(std::move(message), value);
    };
    if (std::find(kWindowFields.begin(), kWindowFields.end(), field) == kWindowFields.end()) {
      ok = false;
      const std::string best = param::closestMatch(field, {kWindowFields.begin(), kWindowFields.end()});
      fail("unknown key '" + field + "' in " + name + param::didYouMean(best) +
               "; expected uav, start_s and optionally end_s",
           key_node);
      continue;
    }
    if (!seen.insert(field).second) {
      ok = false;
      fail("duplicate key '" + field_name + "'", key_node);
      continue;
    }
    if (field == "uav") {
      uav = readNumber(windowUavParam(), value, field_name, field_fail);
    } else if (field == "start_s") {
      start_s = readNumber(windowStartParam(), value, field_name, field_fail);
    } else {
      end_s = readNumber(windowEndParam(), value, field_name, field_fail);
      end_node.emplace(value);
    }
  }
  for (const char* required : {"uav", "start_s"}) {
    if (seen.count(required) == 0) {
      ok = false;
      fail(name + " has no " + required + "; expected a map such as " + kWindowExample, element);
    }
  }
  if (start_s && end_s && !(*end_s > *start_s)) {
    ok = false;
    fail(name + ".end_s = " + formatYamlNumber(*end_s) + " s must be > " + name + ".start_s = " +
             formatYamlNumber(*start_s) + " s: the outage would be empty (leave end_s out for one that never ends)",
         *end_node);
  }
  if (!ok || !uav || !start_s) return std::nullopt;
  GnssWindow window;
  window.uav = static_cast<int>(*uav);
  window.start_s = *start_s;
  if (end_s) window.end_s = *end_s;
  return window;
}

void assignWindows(const Param& p, const Entry& e, Scenario& s, Report& report) {
  std::vector<GnssWindow> windows;
  bool ok = true;
  std::size_t index = 0;
  for (const YAML::Node& element : e.value) {
    const std::string name = p.key + "[" + std::to_string(index++) + "]";
    const auto fail = [&](std::string message, const YAML::Node& at) {
      ok = false;
      const std::string where = e.from_file && !locationOf(at).empty() ? locationOf(at) : e.where;
      report.addFor(p.key, std::move(message) + where);
    };
    if (auto window = readWindow(element, name, fail)) windows.push_back(*window);
  }
  if (ok) p.set_windows(s, std::move(windows));
}

// Assigns the value of a scenario (non-agent) entry, or reports why it cannot.
void assign(const Param& p, const Entry& e, Scenario& s, Report& report) {
  const auto fail = [&](std::string message) { report.addFor(p.key, std::move(message) + e.where); };
  const YAML::Node& value = e.value;
  if (value.IsNull()) return fail(p.key + " has no value; expected " + expectation(p));
  if (p.kind == Kind::kIndexList) {
    if (!value.IsSequence()) return fail(p.key + " must be " + expectation(p) + ", got " + nodeKindName(value));
    return assignList(p, e, s, report);
  }
  if (p.kind == Kind::kWindowList) {
    if (!value.IsSequence()) return fail(p.key + " must be " + expectation(p) + ", got " + nodeKindName(value));
    return assignWindows(p, e, s, report);
  }
  if (!value.IsScalar()) return fail(p.key + " must be " + expectation(p) + ", got " + nodeKindName(value));
  const std::string& text = value.Scalar();

  switch (p.kind) {
    case Kind::kChoice: {
      const auto it = std::find(p.choices.begin(), p.choices.end(), text);
      if (it == p.choices.end()) {
        return fail(p.key + " = '" + text + "' is not valid; expected one of: " + join(p.choices, ", "));
      }
      return p.set_choice(s, static_cast<std::size_t>(it - p.choices.begin()));
    }
    case Kind::kBool: {
      if (isQuoted(value)) return fail(p.key + " = \"" + text + "\" is a string; expected true or false");
      if (text == "true" || text == "True" || text == "TRUE") return p.set_bool(s, true);
      if (text == "false" || text == "False" || text == "FALSE") return p.set_bool(s, false);
      return fail(p.key + " = '" + text + "' is not valid; expected true or false");
    }
    case Kind::kSeed:
      if (isQuoted(value)) return fail(p.key + " = \"" + text + "\" is a string; expected " + expectation(p));
      return assignSeed(p, e, s, fail);
    case Kind::kReal:
    case Kind::kInteger:
      if (const auto v = readNumber(p, value, p.key, fail)) p.set_number(s, *v);
      return;
    case Kind::kIndexList:
    case Kind::kWindowList:
      return;
  }
}

// ------------------------------------------------------------------------------------------------------------
// Cross-field rules of the scenario (the agent's own are checked by the agent's loader).

void checkRelations(const Scenario& s, Report& report) {
  const auto ok = [&](std::initializer_list<const char*> keys) {
    return std::none_of(keys.begin(), keys.end(), [&](const char* k) { return report.isBad(k); });
  };

  for (const char* key : {"imu.rate_hz", "mps.rate_hz", "gnss.rate_hz"}) {
    if (!ok({key, "dynamics.rate_hz"})) continue;
    const double rate = findParam(key)->get_number(s);
    const double ratio = s.dynamics.rate_hz / rate;
    const double steps = std::round(ratio);
    if (steps >= 1.0 && std::fabs(ratio - steps) <= 1e-9 * steps) continue;
    std::ostringstream ratio_text;
    ratio_text.precision(4);
    ratio_text << ratio;
    report.add(std::string(key) + " = " + formatYamlNumber(rate) + " Hz must divide dynamics.rate_hz = " +
               formatYamlNumber(s.dynamics.rate_hz) +
               " Hz exactly: the sensor samples every n-th simulation step, and " +
               formatYamlNumber(s.dynamics.rate_hz) + " / " + formatYamlNumber(rate) + " = " + ratio_text.str() +
               " is not a whole number >= 1");
  }

  if (ok({"gnss.dropout_start_s", "gnss.dropout_end_s"}) && !(s.gnss.dropout_end_s > s.gnss.dropout_start_s)) {
    report.add("gnss.dropout_end_s = " + formatYamlNumber(s.gnss.dropout_end_s) +
               " s must be > gnss.dropout_start_s = " + formatYamlNumber(s.gnss.dropout_start_s) +
               " s: the outage would be empty (to run without a dropout, set gnss.dropout_start_s >= duration_s)");
  }

  if (ok({"gnss.keep_uavs", "uav_count"})) {
    std::set<int> listed;
    for (const int id : s.gnss.keep_uavs) {
      if (id < 0 || id >= s.uav_count) {
        report.add("gnss.keep_uavs lists UAV " + std::to_string(id) + ", but the UAV indices are 0.." +
                   std::to_string(s.uav_count - 1) + " (uav_count = " + std::to_string(s.uav_count) + ")");
      } else if (!listed.insert(id).second) {
        report.add("gnss.keep_uavs lists UAV " + std::to_string(id) + " more than once");
      }
    }
  }

  if (ok({"gnss.windows", "uav_count"})) {
    for (std::size_t i = 0; i < s.gnss.windows.size(); ++i) {
      const int id = s.gnss.windows[i].uav;
      if (id >= 0 && id < s.uav_count) continue;
      report.add("gnss.windows[" + std::to_string(i) + "].uav = " + std::to_string(id) +
                 " is not a UAV of the swarm: the UAV indices are 0.." + std::to_string(s.uav_count - 1) +
                 " (uav_count = " + std::to_string(s.uav_count) + ")");
    }
  }

  if (ok({"formation.spacing_m", "mps.range_m"}) && !(s.formation.spacing_m < s.mps.range_m)) {
    report.add("formation.spacing_m = " + formatYamlNumber(s.formation.spacing_m) + " m must be < mps.range_m = " +
               formatYamlNumber(s.mps.range_m) + " m: otherwise no UAV detects its neighbours");
  }
}

// ------------------------------------------------------------------------------------------------------------
// The agent section: the agent entries are written back as YAML text (yaml-cpp Emitter) in the agent's file
// layout and parsed by swa::agent::parseAgentConfig, which applies the agent's table, bounds and cross-field
// rules. Its messages are then renamed to the scenario's keys and located in the scenario file.

struct AgentTree {
  std::vector<std::pair<std::string, AgentTree>> children;
  const Entry* leaf = nullptr;

  AgentTree& child(const std::string& name) {
    for (auto& c : children) {
      if (c.first == name) return c.second;
    }
    children.emplace_back(name, AgentTree{});
    return children.back().second;
  }
};

void emitValue(YAML::Emitter& out, const YAML::Node& value) {
  if (value.IsScalar()) {
    // Keep a quoted scalar quoted: the agent's loader rejects strings where numbers belong.
    if (isQuoted(value)) {
      out << YAML::DoubleQuoted << value.Scalar();
    } else {
      out << value.Scalar();
    }
  } else if (value.IsNull() || !value.IsDefined()) {
    out << YAML::Null;
  } else {
    out << value;  // a sequence or map: the agent's loader reports the wrong shape
  }
}

void emitTree(YAML::Emitter& out, const AgentTree& tree) {
  out << YAML::BeginMap;
  for (const auto& [name, child] : tree.children) {
    out << YAML::Key << name << YAML::Value;
    if (child.leaf != nullptr) {
      emitValue(out, child.leaf->value);
    } else {
      emitTree(out, child);
    }
  }
  out << YAML::EndMap;
}

bool isKeyChar(char c) { return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_' || c == '.'; }

// Rewrites an agent message ("formation.k = 0 is out of range [1, 16] (line 3, column 6)") into the scenario's
// terms ("agent.k = 0 is out of range [1, 16] (line 12, column 6)").
std::string translateAgentProblem(std::string message, Entries& entries) {
  // Drop the location within the generated text.
  const std::string line_marker = " (line ";
  const auto at = message.rfind(line_marker);
  if (at != std::string::npos && message.back() == ')' && message.find(", column ", at) != std::string::npos) {
    message.erase(at);
  }
  const auto& leaves = agentKeys().leaves;
  std::string out;
  std::string first_key;
  std::size_t i = 0;
  while (i < message.size()) {
    if (!isKeyChar(message[i])) {
      out += message[i++];
      continue;
    }
    std::size_t j = i;
    while (j < message.size() && isKeyChar(message[j])) ++j;
    std::string token = message.substr(i, j - i);
    std::string trailing;
    while (!token.empty() && token.back() == '.') {
      trailing += '.';
      token.pop_back();
    }
    if (std::find(leaves.begin(), leaves.end(), token) != leaves.end()) {
      const std::string key = std::string(kAgentPrefix) + token;
      if (first_key.empty() && i == 0) first_key = key;
      const Entry* entry = findEntry(entries, key);
      out += entry != nullptr ? entry->written : key;
    } else {
      out += token;
    }
    out += trailing;
    i = j;
  }
  // Locate value problems; a relation between two keys ("a = 1 must be < b = 2: why") names both instead.
  const bool relation = out.find(" must be <") != std::string::npos;
  if (!first_key.empty() && !relation) {
    if (const Entry* entry = findEntry(entries, first_key)) out += entry->where;
  }
  return out;
}

void applyAgent(Entries& entries, Scenario& s, Report& report, bool check_relations) {
  // The agents' desired spacing is the formation spacing unless the radius is given.
  if (findEntry(entries, kRadiusKey) == nullptr && !report.isBad("formation.spacing_m")) {
    Entry derived;
    derived.key = kRadiusKey;
    derived.written = std::string(kRadiusKey) + " (= formation.spacing_m)";
    derived.value = YAML::Node(formatYamlReal(s.formation.spacing_m));
    entries.push_back(std::move(derived));
  }

  AgentTree root;
  for (const Entry& e : entries) {
    if (!isAgentKey(e.key)) continue;
    AgentTree* node = &root;
    std::string rest = e.key.substr(kAgentPrefix.size());
    for (auto dot = rest.find('.'); dot != std::string::npos; dot = rest.find('.')) {
      node = &node->child(rest.substr(0, dot));
      rest.erase(0, dot + 1);
    }
    node->child(rest).leaf = &e;
  }
  YAML::Emitter out;
  emitTree(out, root);
  if (!out.good()) {
    report.add("internal error: the agent section cannot be written as YAML: " + out.GetLastError());
    return;
  }

  try {
    s.agent = agent::parseAgentConfig(out.c_str(), "agent");
  } catch (const ConfigError& error) {
    for (const std::string& problem : error.problems()) {
      std::string translated = translateAgentProblem(problem, entries);
      if (!check_relations && translated.find(" must be <") != std::string::npos) continue;
      report.add(std::move(translated));
    }
  }
}

// ------------------------------------------------------------------------------------------------------------

// `yaml_text` is null when the file could not be read (`report` then already says why).
Scenario buildScenario(const std::string* yaml_text, Report report, const std::string& source,
                       const std::vector<std::string>& overrides) {
  bool file_ok = yaml_text != nullptr;
  Entries entries;
  if (yaml_text != nullptr) {
    std::vector<YAML::Node> documents;
    try {
      documents = YAML::LoadAll(*yaml_text);
    } catch (const YAML::Exception& e) {
      report.add(describeYamlException(e));
      file_ok = false;
    }
    if (documents.size() > 1) {
      report.add("contains " + std::to_string(documents.size()) + " YAML documents; expected one");
      file_ok = false;
    } else if (documents.size() == 1 && param::countKeys(documents.front()) > param::kMaxKeys) {
      report.add("has more than " + std::to_string(param::kMaxKeys) + " keys: not a scenario file");
      file_ok = false;
    } else if (documents.size() == 1 && !documents.front().IsNull()) {
      const YAML::Node& root = documents.front();
      if (root.IsMap()) {
        std::set<std::string> seen;
        flatten(root, "", entries, seen, report);
      } else {
        report.add(std::string("the top level must be a map of parameters (e.g. 'uav_count: 8'), got ") +
                   nodeKindName(root) + locationOf(root));
        file_ok = false;
      }
    }
  }

  applyOverrides(overrides, entries, report);

  Scenario scenario;
  for (const Entry& e : entries) {
    if (const Param* p = findParam(e.key)) assign(*p, e, scenario, report);
  }
  // Relations on top of a file that could not be read would judge defaults the file may have changed.
  if (file_ok) checkRelations(scenario, report);
  applyAgent(entries, scenario, report, file_ok);

  if (!report.empty()) throw ConfigError(source, report.take());
  return scenario;
}

}  // namespace

// ------------------------------------------------------------------------------------------------------------

Scenario parseScenario(const std::string& yaml_text, const std::string& source,
                       const std::vector<std::string>& overrides) {
  return buildScenario(&yaml_text, Report{}, source, overrides);
}

Scenario loadScenario(const std::string& path, const std::vector<std::string>& overrides) {
  Report report;
  std::string problem;
  const std::optional<std::string> text = param::readTextFile(path, "scenario", problem);
  if (text) return buildScenario(&*text, std::move(report), path, overrides);
  report.add(problem);
  return buildScenario(nullptr, std::move(report), path, overrides);
}

std::string scenarioToYaml(const Scenario& scenario) {
  std::vector<param::CommentedLine> lines;
  std::string section;
  for (const Param& p : parameters()) {
    const auto dot = p.key.find('.');
    const std::string this_section = dot == std::string::npos ? "" : p.key.substr(0, dot);
    if (this_section != section && !this_section.empty()) lines.push_back({this_section + ":", ""});
    section = this_section;

    std::string comment;
    switch (p.kind) {
      case Kind::kChoice:
      case Kind::kBool:
        comment = join(p.choices, " | ");
        break;
      case Kind::kIndexList:
        comment = "UAV indices in [0, uav_count)";
        break;
      case Kind::kWindowList:
        comment = "per-UAV outages {uav, start_s, end_s} (end_s .inf = never restored)";
        break;
      case Kind::kReal:
      case Kind::kInteger:
      case Kind::kSeed:
        comment = p.unit.empty() ? "-" : p.unit;
        if (p.allow_infinity) comment += " (.inf = never)";
        break;
    }
    const std::string indent = section.empty() ? "" : "  ";
    const std::string name = p.key.substr(dot == std::string::npos ? 0 : dot + 1);
    if (p.kind == Kind::kWindowList && !p.get_windows(scenario).empty()) {
      // One window per line, so a long list does not push every comment to the right.
      lines.push_back({indent + name + ":", comment});
      for (const GnssWindow& w : p.get_windows(scenario)) lines.push_back({indent + "  - " + formatWindow(w), ""});
      continue;
    }
    lines.push_back({indent + name + ": " + formatValue(p, scenario), comment});
  }

  std::string out = "# SWA scenario: every parameter, as used\n" + param::alignComments(lines);

  out += "agent:                          # the agents' configuration (agent.formation.radius_m given explicitly)\n";
  std::istringstream agent_yaml(agent::toYaml(scenario.agent));
  for (std::string line; std::getline(agent_yaml, line);) {
    if (line.empty() || line.front() == '#') continue;
    out += "  " + line + '\n';
  }
  return out;
}

std::string describeScenarioParameters() {
  const Scenario defaults;
  std::vector<std::vector<std::string>> rows = {{"key", "type", "unit", "default", "range", "meaning"}};
  for (const Param& p : parameters()) {
    rows.push_back({p.key, typeName(p.kind), p.unit.empty() ? "-" : p.unit, formatValue(p, defaults),
                    formatRange(p), p.meaning});
  }
  std::string out =
      "Scenario parameters. In the YAML file a key a.b is written nested (a map 'a:' holding 'b:'); on the\n"
      "command line use --set a.b=value. Ranges: [ ] includes the bound, ( ) excludes it; '-' = dimensionless.\n\n" +
      param::formatTable(rows);
  out +=
      "\nRules between parameters:\n"
      "  - imu.rate_hz, mps.rate_hz and gnss.rate_hz must each divide dynamics.rate_hz exactly.\n"
      "  - gnss.dropout_end_s > gnss.dropout_start_s; gnss.dropout_end_s may be .inf (never restored), the only\n"
      "    key that accepts infinity.\n"
      "  - gnss.keep_uavs: distinct UAV indices in [0, uav_count).\n"
      "  - gnss.windows: extra outages of single UAVs, e.g. [{uav: 3, start_s: 20, end_s: 40}, {uav: 5, start_s: 0}]\n"
      "    (--set gnss.windows='[...]' replaces the whole list). uav in [0, uav_count), 0 <= start_s < end_s;\n"
      "    end_s may be .inf or left out (never restored). A UAV has no GNSS inside the common window (unless it\n"
      "    is in keep_uavs) or inside any of its own windows; windows may overlap.\n"
      "  - formation.spacing_m < mps.range_m.\n"
      "\nAgent parameters: the 'agent:' section takes the agent configuration layout below (e.g. agent.mode,\n"
      "agent.formation.k; --set agent.focal.q_scale=2). Shortcuts: agent.k = agent.formation.k and\n"
      "agent.circle_fit = agent.formation.circle_fit (a file may give a shortcut or its long form, not both).\n"
      "agent.formation.radius_m defaults to formation.spacing_m unless given.\n\n";
  out += agent::describeParameters();
  return out;
}

}  // namespace swa::sim

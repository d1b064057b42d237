#include "swa/agent/config_io.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <limits>
#include <optional>
#include <set>
#include <system_error>
#include <type_traits>
#include <utility>

#include "swa/agent/param_file.h"
#include "swa/agent/param_text.h"
#include "swa/agent/param_yaml.h"

namespace swa::agent {

namespace {

using param::closed;
using param::describeYamlException;
using param::formatNumber;
using param::formatYamlReal;
using param::join;
using param::nodeKindName;
using param::open;
using param::openClosed;
using param::Range;

// ------------------------------------------------------------------------------------------------------------
// The parameter table: every tunable of AgentConfig is declared here exactly once.

enum class Kind { kReal, kInteger, kChoice };

struct Param {
  std::string key;   // dotted, e.g. "formation.radius_m"; top-level keys have no dot
  Kind kind = Kind::kReal;
  std::string unit;  // empty = dimensionless
  Range range{};     // numeric kinds only
  std::vector<std::string> choices;  // kChoice only
  std::string meaning;
  // Numeric kinds: the field as a double (integers up to 2^53 are exact).
  std::function<double(const AgentConfig&)> get_number;
  std::function<void(AgentConfig&, double)> set_number;
  // kChoice: the field as an index into `choices` (choices.size() if the enum holds no listed value).
  std::function<std::size_t(const AgentConfig&)> get_choice;
  std::function<void(AgentConfig&, std::size_t)> set_choice;
};

template <class Section, class Field>
Param number(std::string key, Section AgentConfig::*section, Field Section::*field, std::string unit, Range range,
             std::string meaning) {
  static_assert(std::is_arithmetic_v<Field> && !std::is_same_v<Field, bool>);
  Param p;
  p.key = std::move(key);
  p.kind = std::is_integral_v<Field> ? Kind::kInteger : Kind::kReal;
  p.unit = std::move(unit);
  p.range = range;
  p.meaning = std::move(meaning);
  p.get_number = [section, field](const AgentConfig& c) { return static_cast<double>(c.*section.*field); };
  p.set_number = [section, field](AgentConfig& c, double v) { c.*section.*field = static_cast<Field>(v); };
  return p;
}

// `access` is a generic lambda `[](auto& c) -> auto& { return c.section.field; }`, usable on const and mutable configs.
template <class Enum, std::size_t N, class Access>
Param choice(std::string key, Access access, const std::array<Enum, N>& values, std::string meaning) {
  Param p;
  p.key = std::move(key);
  p.kind = Kind::kChoice;
  p.meaning = std::move(meaning);
  for (const Enum v : values) p.choices.push_back(toString(v));
  p.get_choice = [access, values](const AgentConfig& c) {
    return static_cast<std::size_t>(std::find(values.begin(), values.end(), access(c)) - values.begin());
  };
  p.set_choice = [access, values](AgentConfig& c, std::size_t i) { access(c) = values.at(i); };
  return p;
}

constexpr std::array kModes{Mode::kSwa, Mode::kStandalone, Mode::kAnchored};
constexpr std::array kCircleFits{CircleFit::kFixedRadius, CircleFit::kAlgebraic};
constexpr std::array kNeighbourhoodRules{NeighbourhoodRule::kGabriel, NeighbourhoodRule::kKNearest};

const std::vector<Param>& parameters() {
  using A = AgentConfig;
  using S = SurroundingsConfig;
  using F = FormationConfig;
  using Fo = FocalConfig;
  using C = ControlConfig;
  using An = AnchorConfig;
  using L = LimitsConfig;
  static const std::vector<Param> table = {
      choice("mode", [](auto& c) -> auto& { return c.mode; }, kModes,
                   "swa = relative formation; standalone = dead-reckoning baseline; anchored = swa + GNSS hold"),

      number("surroundings.q_pos_m2", &A::surroundings, &S::q_pos_m2, "m^2", openClosed(0, 100),
             "Q_o position block, per q_ref_dt_s of track prediction"),
      number("surroundings.q_vel_m2ps2", &A::surroundings, &S::q_vel_m2ps2, "m^2/s^2", openClosed(0, 100),
             "Q_o velocity block, per q_ref_dt_s of track prediction"),
      number("surroundings.q_acc_m2ps4", &A::surroundings, &S::q_acc_m2ps4, "m^2/s^4", openClosed(0, 1000),
             "Q_o acceleration block, per q_ref_dt_s of track prediction"),
      number("surroundings.q_ref_dt_s", &A::surroundings, &S::q_ref_dt_s, "s", openClosed(0, 1),
             "prediction step the Q_o blocks refer to (scaled linearly with the actual step)"),
      number("surroundings.r_det_m2", &A::surroundings, &S::r_det_m2, "m^2", openClosed(0, 100),
             "R_o: detection noise used when a detection carries no covariance of its own"),
      number("surroundings.init_vel_var_m2ps2", &A::surroundings, &S::init_vel_var_m2ps2, "m^2/s^2",
             openClosed(0, 100), "velocity variance of a new track"),
      number("surroundings.init_acc_var_m2ps4", &A::surroundings, &S::init_acc_var_m2ps4, "m^2/s^4",
             openClosed(0, 1000), "acceleration variance of a new track"),
      number("surroundings.confirm_hits", &A::surroundings, &S::confirm_hits, "", closed(1, 20),
             "detections (M) before a track may be used as a neighbour"),
      number("surroundings.track_timeout_s", &A::surroundings, &S::track_timeout_s, "s", openClosed(0, 60),
             "a confirmed track is removed after this long without a detection"),
      number("surroundings.tentative_timeout_s", &A::surroundings, &S::tentative_timeout_s, "s", openClosed(0, 60),
             "a tentative track is removed after this long without a detection"),
      number("surroundings.gate_probability", &A::surroundings, &S::gate_probability, "", open(0, 1),
             "chi-square gate probability (2 dof) for anonymous association"),

      number("formation.radius_m", &A::formation, &F::radius_m, "m", openClosed(0, 1000),
             "r: desired distance to the neighbours (radius of the fitted circle)"),
      choice("formation.neighbourhood", [](auto& c) -> auto& { return c.formation.neighbourhood; },
             kNeighbourhoodRules,
             "gabriel = tracks with no other track inside the circle on the segment to them as diameter; "
             "k_nearest = the k nearest tracks"),
      number("formation.k", &A::formation, &F::k, "", closed(1, 16),
             "k_nearest only: number of nearest neighbours used for the floating frame"),
      number("formation.sensing_range_m", &A::formation, &F::sensing_range_m, "m", openClosed(0, 10000),
             "tracks farther than this are not neighbours"),
      number("formation.max_edge_factor", &A::formation, &F::max_edge_factor, "", closed(1, 100),
             "gabriel only: neighbours other than the nearest must be closer than this times r"),
      choice("formation.circle_fit", [](auto& c) -> auto& { return c.formation.circle_fit; }, kCircleFits,
              "fit for n >= 3 neighbours; algebraic = the paper's Kasa fit (collapses, k = 3)"),
      number("formation.far_neighbour_weight", &A::formation, &F::far_neighbour_weight, "", openClosed(0, 1),
             "fixed_radius fit: weight of the neighbours beyond the two nearest (which weigh 1)"),

      number("focal.tau_s", &A::focal, &Fo::tau_s, "s", openClosed(0, 60),
             "tau: time constant of the velocity damping exp(-dt/tau) of the focal UAV model"),
      number("focal.q_pos_m2", &A::focal, &Fo::q_pos_m2, "m^2", openClosed(0, 100),
             "Q_f position block, per q_ref_dt_s, before q_scale"),
      number("focal.q_vel_m2ps2", &A::focal, &Fo::q_vel_m2ps2, "m^2/s^2", openClosed(0, 100),
             "Q_f velocity block, per q_ref_dt_s, before q_scale"),
      number("focal.q_acc_m2ps4", &A::focal, &Fo::q_acc_m2ps4, "m^2/s^4", openClosed(0, 1000),
             "Q_f acceleration block, per q_ref_dt_s, before q_scale"),
      number("focal.q_scale", &A::focal, &Fo::q_scale, "", openClosed(0, 100),
             "factor applied to all of Q_f (1 = Table I)"),
      number("focal.q_ref_dt_s", &A::focal, &Fo::q_ref_dt_s, "s", openClosed(0, 1),
             "prediction step the Q_f blocks refer to (scaled linearly with the actual step)"),
      number("focal.r_pos_m2", &A::focal, &Fo::r_pos_m2, "m^2", openClosed(0, 100),
             "R_c: noise of the floating-frame position measurement"),
      number("focal.r_acc_m2ps4", &A::focal, &Fo::r_acc_m2ps4, "m^2/s^4", openClosed(0, 1000),
             "R_a: noise of the tilt-derived acceleration measurement"),
      number("focal.q_c_mps2", &A::focal, &Fo::q_c_mps2, "m/s^2/rad", openClosed(0, 50),
             "q_c: lateral acceleration per radian of tilt"),
      number("focal.frame_timeout_s", &A::focal, &Fo::frame_timeout_s, "s", openClosed(0, 600),
             "without a floating frame for this long, dead reckoning is no longer trusted"),
      number("focal.bias_window_s", &A::focal, &Fo::bias_window_s, "s", closed(0, 3600),
             "IMU-bias removal: window of the running mean subtracted from the tilt acceleration (0 = off); "
             "assumes a hovering UAV's acceleration averages to zero"),
      number("focal.bias_freeze_speed_mps", &A::focal, &Fo::bias_freeze_speed_mps, "m/s", openClosed(0, 50),
             "the IMU-bias mean is frozen while the commanded speed exceeds this"),
      number("focal.bias_freeze_hold_s", &A::focal, &Fo::bias_freeze_hold_s, "s", closed(0, 600),
             "the IMU-bias mean stays frozen this long after the commanded speed last exceeded "
             "bias_freeze_speed_mps"),

      number("control.k_p", &A::control, &C::k_p, "1/s", closed(0, 20), "position feedback gain"),
      number("control.k_v", &A::control, &C::k_v, "", closed(0, 10), "velocity feedback gain"),
      number("control.v_max_mps", &A::control, &C::v_max_mps, "m/s", openClosed(0, 50),
             "saturation of the desired velocity |v_d|"),

      number("anchor.gain", &A::anchor, &An::gain, "", closed(0, 10),
             "weight of the absolute (GNSS) hold added to the relative command in anchored mode"),
      number("anchor.gnss_min_std_m", &A::anchor, &An::gnss_min_std_m, "m", openClosed(0, 100),
             "floor for the standard deviation a GNSS fix claims"),

      number("limits.max_detections", &A::limits, &L::max_detections, "", closed(1, 1024),
             "a detection set larger than this is rejected whole"),
      number("limits.max_target_id", &A::limits, &L::max_target_id, "",
             closed(1, static_cast<double>(std::numeric_limits<int>::max())),
             "detections with a target ID above this are treated as corrupt"),
      number("limits.max_tilt_rad", &A::limits, &L::max_tilt_rad, "rad", openClosed(0, 1.5),
             "|roll|, |pitch| beyond this are not treated as lateral flight"),
      number("limits.max_abs_position_m", &A::limits, &L::max_abs_position_m, "m", openClosed(0, 1e9),
             "detections and GNSS fixes farther than this are corrupt"),
      number("limits.max_abs_heading_rad", &A::limits, &L::max_abs_heading_rad, "rad", openClosed(0, 1e3),
             "IMU headings beyond +- this are corrupt"),
      number("limits.max_stamp_jump_s", &A::limits, &L::max_stamp_jump_s, "s", openClosed(0, 3600),
             "a sample stamped more than this after the previous one of its stream (or this far from the IMU's "
             "clock) is not trusted"),
      number("limits.resync_samples", &A::limits, &L::resync_samples, "", closed(2, 100),
             "consecutive samples of a consistent new timeline after which a stream re-synchronises to it"),
  };
  return table;
}

// Constraints between parameters, checked after every parameter is individually valid.
struct Relation {
  const char* lhs;
  bool strict;  // lhs < rhs if true, lhs <= rhs otherwise
  const char* rhs;
  const char* why;
};
constexpr std::array kRelations{
    Relation{"surroundings.tentative_timeout_s", false, "surroundings.track_timeout_s",
             "a tentative track must not outlive a confirmed one"},
    Relation{"formation.radius_m", true, "formation.sensing_range_m",
             "neighbours sit about r apart, so they must be within sensing range"},
    Relation{"formation.sensing_range_m", false, "limits.max_abs_position_m",
             "otherwise detections within sensing range are rejected as corrupt"},
};

// ------------------------------------------------------------------------------------------------------------
// Lookup and formatting.

const Param* findParam(const std::string& key) {
  for (const Param& p : parameters()) {
    if (p.key == key) return &p;
  }
  return nullptr;
}

bool isSection(const std::string& key) {
  const std::string prefix = key + ".";
  return std::any_of(parameters().begin(), parameters().end(),
                     [&](const Param& p) { return param::startsWith(p.key, prefix); });
}

std::vector<std::string> sectionNames() {
  std::vector<std::string> names;
  for (const Param& p : parameters()) {
    const auto dot = p.key.find('.');
    if (dot == std::string::npos) continue;
    std::string section = p.key.substr(0, dot);
    if (std::find(names.begin(), names.end(), section) == names.end()) names.push_back(std::move(section));
  }
  return names;
}

std::string formatValue(const Param& p, const AgentConfig& config) {
  switch (p.kind) {
    case Kind::kChoice: {
      const std::size_t i = p.get_choice(config);
      return i < p.choices.size() ? p.choices[i] : "<invalid>";
    }
    case Kind::kInteger:
      return std::to_string(static_cast<long long>(p.get_number(config)));
    case Kind::kReal:
      return formatNumber(p.get_number(config));
  }
  return {};
}

std::string formatRange(const Param& p) {
  if (p.kind == Kind::kChoice) return join(p.choices, "|");
  return param::formatRange(p.range, p.kind == Kind::kInteger);
}

std::string unitSuffix(const Param& p) { return p.unit.empty() ? "" : " " + p.unit; }

const char* typeName(Kind kind) {
  switch (kind) {
    case Kind::kReal:
      return "real";
    case Kind::kInteger:
      return "integer";
    case Kind::kChoice:
      return "choice";
  }
  return "";
}

std::string expectation(const Param& p) {
  switch (p.kind) {
    case Kind::kReal:
      return "a number" + (p.unit.empty() ? std::string() : " in " + p.unit) + " within " + formatRange(p);
    case Kind::kInteger:
      return "an integer within " + formatRange(p);
    case Kind::kChoice:
      return "one of: " + join(p.choices, ", ");
  }
  return {};
}

// Why `v` (shown to the user as `shown`) is not a valid value of numeric parameter `p`, if it is not.
std::optional<std::string> numberProblem(const Param& p, double v, const std::string& shown) {
  return param::numberProblem(p.key, v, shown, p.kind == Kind::kInteger, p.range, formatRange(p) + unitSuffix(p));
}

std::string unknownKeyMessage(const std::string& key) {
  std::vector<std::string> keys;
  for (const Param& p : parameters()) keys.push_back(p.key);
  std::vector<std::string> candidates = sectionNames();
  candidates.insert(candidates.end(), keys.begin(), keys.end());
  std::string best = param::closestMatch(key, candidates);
  if (best.empty()) best = param::sameLeafMatch(key, keys);  // right name, wrong section (e.g. "focal.radius_m")?
  return param::unknownKeyMessage(key, best);
}

// ------------------------------------------------------------------------------------------------------------
// Problem collection and assignment.

class Report {
 public:
  explicit Report(bool show_locations) : show_locations_(show_locations) {}

  void add(std::string message, const YAML::Node* at = nullptr) {
    if (show_locations_ && at != nullptr) message += param::locationOf(*at);
    problems_.push_back(std::move(message));
  }
  // A problem with the value of parameter `key`: relations involving it are not checked.
  void addFor(const std::string& key, std::string message, const YAML::Node* at = nullptr) {
    bad_keys_.insert(key);
    add(std::move(message), at);
  }
  bool isBad(const std::string& key) const { return bad_keys_.count(key) > 0; }
  bool empty() const { return problems_.empty(); }
  std::vector<std::string> take() { return std::move(problems_); }

 private:
  bool show_locations_;
  std::vector<std::string> problems_;
  std::set<std::string> bad_keys_;
};

// Assigns the YAML value of parameter `p` to `config`, or reports why it cannot.
void assign(const Param& p, const YAML::Node& value, AgentConfig& config, Report& report) {
  const auto fail = [&](std::string message) { report.addFor(p.key, std::move(message), &value); };
  if (value.IsNull()) return fail(p.key + " has no value; expected " + expectation(p));
  if (!value.IsScalar()) return fail(p.key + " must be " + expectation(p) + ", got " + nodeKindName(value));
  const std::string& text = value.Scalar();

  if (p.kind == Kind::kChoice) {
    const auto it = std::find(p.choices.begin(), p.choices.end(), text);
    if (it == p.choices.end()) {
      return fail(p.key + " = '" + text + "' is not valid; expected one of: " + join(p.choices, ", "));
    }
    p.set_choice(config, static_cast<std::size_t>(it - p.choices.begin()));
    return;
  }

  double number = 0.0;
  if (auto problem = param::readNumber(value, p.key, expectation(p), number)) return fail(std::move(*problem));
  if (auto problem = numberProblem(p, number, text)) return fail(std::move(*problem));
  p.set_number(config, number);
}

void checkRelations(const AgentConfig& config, Report& report) {
  for (const Relation& r : kRelations) {
    if (report.isBad(r.lhs) || report.isBad(r.rhs)) continue;
    const Param& lhs = *findParam(r.lhs);
    const Param& rhs = *findParam(r.rhs);
    const double a = lhs.get_number(config);
    const double b = rhs.get_number(config);
    if (r.strict ? a < b : a <= b) continue;
    report.add(lhs.key + " = " + formatValue(lhs, config) + " must be " + (r.strict ? "<" : "<=") + " " + rhs.key +
               " = " + formatValue(rhs, config) + ": " + r.why);
  }
}

// Applies every key of a YAML map whose keys live under `prefix` ("" for the top level).
void applyMap(const YAML::Node& map, const std::string& prefix, AgentConfig& config, Report& report,
              std::set<std::string>& seen) {
  for (const auto& entry : map) {
    const YAML::Node& key_node = entry.first;
    const YAML::Node& value = entry.second;
    if (!key_node.IsScalar()) {
      report.add("a key " + (prefix.empty() ? std::string("at the top level") : "under '" + prefix + "'") +
                     " is " + nodeKindName(key_node) + ", not a name",
                 &key_node);
      continue;
    }
    const std::string& name = key_node.Scalar();
    const std::string key = prefix.empty() ? name : prefix + "." + name;
    if (!seen.insert(key).second) {
      report.addFor(key, "duplicate key '" + key + "'", &key_node);
      continue;
    }
    if (name.find('.') != std::string::npos) {
      if (findParam(key) != nullptr || isSection(key)) {
        report.add("dotted key '" + key + "' must be written nested (a '" + key.substr(0, key.find('.')) +
                       ":' map), as in the example file",
                   &key_node);
      } else {
        report.add(unknownKeyMessage(key), &key_node);
      }
      continue;
    }
    if (const Param* p = findParam(key)) {
      assign(*p, value, config, report);
    } else if (isSection(key)) {
      if (value.IsMap()) {
        applyMap(value, key, config, report, seen);
      } else if (!value.IsNull()) {  // an empty section ("formation:") keeps the defaults
        report.add("'" + key + "' must be a map of parameters, got " + nodeKindName(value), &value);
      }
    } else {
      report.add(unknownKeyMessage(key), &key_node);
    }
  }
}

// One `--set` entry; problems go to `report`, `config` is modified only if the value is valid.
void overrideOne(AgentConfig& config, const std::string& key, const std::string& text, Report& report) {
  const Param* p = findParam(key);
  if (p == nullptr) {
    if (isSection(key)) {
      const std::string prefix = key + ".";
      const auto first = std::find_if(parameters().begin(), parameters().end(),
                                      [&](const Param& q) { return param::startsWith(q.key, prefix); });
      report.add("'" + key + "' is a group of parameters, not a parameter; set one of them, e.g. '" + first->key + "'");
    } else {
      report.add(unknownKeyMessage(key));
    }
    return;
  }
  YAML::Node value;
  try {
    value = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    report.addFor(key, key + " = '" + text + "' is not a YAML scalar: " + e.msg);
    return;
  }
  assign(*p, value, config, report);
}

std::string joinWithSource(const std::string& source, const std::vector<std::string>& problems) {
  std::string text;
  for (const std::string& problem : problems) {
    if (!text.empty()) text += '\n';
    text += source + ": " + problem;
  }
  return text;
}

}  // namespace

// ------------------------------------------------------------------------------------------------------------

ConfigError::ConfigError(std::string source, std::vector<std::string> problems)
    : ConfigError(Summarised{}, std::move(source), param::summariseProblems(problems)) {}

ConfigError::ConfigError(Summarised, std::string source, std::vector<std::string> problems)
    : std::runtime_error(joinWithSource(source, problems)), source_(std::move(source)),
      problems_(std::move(problems)) {}

AgentConfig parseAgentConfig(const std::string& yaml_text, const std::string& source_name) {
  std::vector<YAML::Node> documents;
  try {
    documents = YAML::LoadAll(yaml_text);
  } catch (const YAML::Exception& e) {
    throw ConfigError(source_name, {describeYamlException(e)});
  }

  AgentConfig config;
  Report report(/*show_locations=*/true);
  if (documents.size() > 1) {
    report.add("contains " + std::to_string(documents.size()) + " YAML documents; expected one");
  } else if (documents.size() == 1 && param::countKeys(documents.front()) > param::kMaxKeys) {
    report.add("has more than " + std::to_string(param::kMaxKeys) + " keys: not a configuration file");
  } else if (documents.size() == 1 && !documents.front().IsNull()) {
    const YAML::Node& root = documents.front();
    if (root.IsMap()) {
      std::set<std::string> seen;
      applyMap(root, "", config, report, seen);
      checkRelations(config, report);
    } else {
      report.add(std::string("the top level must be a map of parameters (e.g. 'formation:'), got ") +
                     nodeKindName(root),
                 &root);
    }
  }
  if (!report.empty()) throw ConfigError(source_name, report.take());
  return config;
}

AgentConfig loadAgentConfig(const std::string& yaml_path) {
  std::string problem;
  const std::optional<std::string> text = param::readTextFile(yaml_path, "configuration", problem);
  if (!text) throw ConfigError(yaml_path, {problem});
  return parseAgentConfig(*text, yaml_path);
}

void applyOverride(AgentConfig& config, const std::string& dotted_key, const std::string& value) {
  AgentConfig updated = config;
  Report report(/*show_locations=*/false);
  overrideOne(updated, dotted_key, value, report);
  if (report.empty()) checkRelations(updated, report);
  if (!report.empty()) throw ConfigError("--set", report.take());
  config = updated;
}

AgentConfig applyOverrides(AgentConfig config, const std::vector<std::string>& key_eq_value) {
  Report report(/*show_locations=*/false);
  for (const std::string& entry : key_eq_value) {
    const auto eq = entry.find('=');
    if (eq == std::string::npos || eq == 0) {
      report.add("malformed override '" + entry + "'; expected key=value, e.g. formation.k=2");
      continue;
    }
    overrideOne(config, entry.substr(0, eq), entry.substr(eq + 1), report);
  }
  checkRelations(config, report);
  if (!report.empty()) throw ConfigError("--set", report.take());
  return config;
}

void validateAgentConfig(const AgentConfig& config, const std::string& source_name) {
  Report report(/*show_locations=*/false);
  for (const Param& p : parameters()) {
    if (p.kind == Kind::kChoice) {
      if (p.get_choice(config) >= p.choices.size()) {
        report.addFor(p.key, p.key + " holds a value that is not one of: " + join(p.choices, ", "));
      }
    } else if (auto problem = numberProblem(p, p.get_number(config), formatValue(p, config))) {
      report.addFor(p.key, std::move(*problem));
    }
  }
  checkRelations(config, report);
  if (!report.empty()) throw ConfigError(source_name, report.take());
}

std::string describeParameters() {
  const AgentConfig defaults;
  std::vector<std::vector<std::string>> rows = {{"key", "type", "unit", "default", "range", "meaning"}};
  for (const Param& p : parameters()) {
    rows.push_back({p.key, typeName(p.kind), p.unit.empty() ? "-" : p.unit, formatValue(p, defaults),
                    formatRange(p), p.meaning});
  }
  return "Agent parameters. In the YAML file a key a.b is written nested (a map 'a:' holding 'b:'); on the command\n"
         "line use --set a.b=value. Ranges: [ ] includes the bound, ( ) excludes it; '-' = dimensionless.\n\n" +
         param::formatTable(rows);
}

std::string toYaml(const AgentConfig& config) {
  std::vector<param::CommentedLine> lines;
  std::string section;
  for (const Param& p : parameters()) {
    const auto dot = p.key.find('.');
    const std::string this_section = dot == std::string::npos ? "" : p.key.substr(0, dot);
    if (this_section != section && !this_section.empty()) lines.push_back({this_section + ":", ""});
    section = this_section;

    std::string value;
    std::string comment;
    switch (p.kind) {
      case Kind::kChoice:
        value = formatValue(p, config);
        comment = join(p.choices, " | ");
        break;
      case Kind::kInteger:
        value = formatValue(p, config);
        comment = p.unit;
        break;
      case Kind::kReal:
        value = formatYamlReal(p.get_number(config));
        comment = p.unit;
        break;
    }
    const std::string indent = section.empty() ? "" : "  ";
    lines.push_back({indent + p.key.substr(dot == std::string::npos ? 0 : dot + 1) + ": " + value, comment});
  }

  return "# SWA agent configuration: every parameter, as used\n" + param::alignComments(lines);
}

}  // namespace swa::agent

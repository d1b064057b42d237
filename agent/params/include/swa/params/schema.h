#pragma once
// The parameter engine's vocabulary. A Schema declares every parameter of one file layout (the agent
// configuration, the scenario) once: key, kind, unit, range, meaning, and the rules between parameters. Values are
// held by key while a file is read; table.h binds a Schema to the struct it fills. Nothing here includes yaml-cpp.

#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "swa/params/text.h"

namespace swa::params {

enum class Kind { kReal, kInteger, kSeed, kBool, kChoice, kText, kIntList, kRecordList };
// kText: a name such as a ROS frame id, or a comma-separated list of them: up to kMaxTextChars of kTextChars, or empty.
inline constexpr std::size_t kMaxTextChars = 256;
inline constexpr const char* kTextChars = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789_./,-";

// One kRecordList element: the values of Spec::fields in their order, a field of `components` numbers taking that many
// slots (recordSlot); a field left out of an element that gives another alternative holds NaN.
using Record = std::vector<double>;
// kReal and kInteger hold a double (integers up to 2^53 are exact), kSeed a uint64, kChoice the chosen name, kText
// the text.
using Value = std::variant<double, std::uint64_t, bool, std::string, std::vector<long long>, std::vector<Record>>;
using Values = std::map<std::string, Value>;  // by dotted key

struct Spec {
  std::string key;  // dotted: "formation.radius_m" is written nested in a file (a 'formation:' map)
  Kind kind = Kind::kReal;
  std::string unit;                  // empty = dimensionless
  Range range{};                     // numeric kinds, and each element of a kIntList
  bool allow_infinity = false;       // kReal: +.inf is valid, meaning "never"
  std::vector<std::string> choices;  // kChoice
  std::string meaning;
  // kRecordList: the fields of one element (kReal or kInteger specs keyed by field name); a field with a default
  // may be left out. `later` > `earlier` must hold in every element, for the reason `order_why`.
  std::vector<Spec> fields;
  // A field of a record: written as a list of this many numbers ("velocity_mps: [3, 0]"), each within `range`.
  std::size_t components = 1;
  // kRecordList: the forms an element may take, each a set of field names: an element gives every field of exactly
  // one of them and none of the others' ("{velocity_mps, duration_s}" or "{to_m, speed_mps}"). Fields named in no
  // form are as without forms. Empty: one form, every field.
  std::vector<std::vector<std::string>> forms;
  std::optional<double> default_value;
  std::string earlier, later, order_why;
  std::string example;     // kRecordList: one element as YAML, for messages
  std::string expected;    // lists: what a valid value is, in messages ("a list of UAV indices such as [0] ...")
  std::string range_text;  // lists: the range column of the description
  std::string comment;     // lists: the comment of the dump
  std::string type_name;   // kRecordList: the type column of the description
};

inline Spec makeSpec(std::string key, Kind kind, std::string unit = "", Range range = {}) {
  Spec s;
  s.key = std::move(key);
  s.kind = kind;
  s.unit = std::move(unit);
  s.range = range;
  return s;
}

// lhs < rhs (strict) or lhs <= rhs between two numeric parameters.
struct Relation {
  std::string lhs;
  bool strict;
  std::string rhs;
  std::string why;
};

// A rule between parameters that is more than an order: `run` adds a message per violation. Skipped while any of
// `keys` has an invalid value of its own.
struct Check {
  std::vector<std::string> keys;
  std::function<void(const Values&, std::vector<std::string>& problems)> run;
};

// `key` is used only while the choice parameter `when` holds one of `values` or, with no `values`, while the number
// `when` is not 0 (0 = off) or the text `when` is not empty; `what` names that case in messages ("the k_nearest rule").
// Giving `key` while it changes nothing is an error, unless the file gave it and a --set of `when` turned it off (a
// study's sweep over the rule); the dump writes such a key as a comment.
struct Applies {
  std::string key;
  std::string when;
  std::vector<std::string> values;
  std::string what;
};

// A second spelling of a parameter; giving both in one file is an error, a --set of either replaces the other.
struct Alias {
  std::string alias;
  std::string key;
};

// `key` takes the value of `source` unless it is given (a file or a --set); messages call it "key (= source)".
struct Derived {
  std::string key;
  std::string source;
};

struct Schema {
  std::string title;              // "SWA scenario": first line of the dump and of the description
  std::string file_kind;          // "scenario": "... is not a scenario file"
  std::string top_level_example;  // "uav_count: 8"
  std::string override_example;   // "uav_count=16"
  std::string notes;              // the description's rules between parameters, in words
  std::vector<Spec> specs;
  std::vector<Relation> relations;
  std::vector<Check> checks;
  std::vector<Applies> applies;
  std::vector<Alias> aliases;
  std::vector<Derived> derived;
  std::map<std::string, std::string> mounts;  // prefix -> comment of its section in the dump
  // Top-level sections another reader owns (the scenario's `study:`, read by swa_batch through section.h): a file
  // may carry them and this schema skips them; --set cannot reach them.
  std::vector<std::string> foreign_sections;

  const Spec* find(const std::string& key) const;
  // The first rule under which `key` is unused with these values, or nullptr.
  const Applies* unused(const std::string& key, const Values& values) const;
  // Puts every parameter, relation, alias and derived default of `inner` under "prefix." (the scenario's `agent:`
  // section is the agent's configuration schema). Checks are not mounted: they belong to the outer schema.
  void mount(const std::string& prefix, const Schema& inner, const std::string& comment);
};

// Whether the values of `a.when` turn `a.key` off.
bool turnsOff(const Applies& a, const Values& values);

// The first slot of field `field` in a record of `s` (fields before it may take several), and the slots of a record.
std::size_t recordSlot(const Spec& s, std::size_t field);
std::size_t recordSlots(const Spec& s);

// Typed reads of a Values map, for checks.
double number(const Values& values, const std::string& key);
const std::vector<long long>& intList(const Values& values, const std::string& key);
const std::vector<Record>& records(const Values& values, const std::string& key);

}  // namespace swa::params

// Reading parameters: a YAML file and --set overrides become flat entries (key, value node, where it was written),
// each entry is checked against its Spec into a Value, then the rules between parameters are judged. Every problem
// is collected; the first one does not hide the others.

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <limits>
#include <list>
#include <set>

#include "spec_text.h"
#include "yaml_node.h"
#include "swa/params/engine.h"
#include "swa/params/file.h"

namespace swa::params {

namespace {

using namespace detail;

constexpr std::size_t kMaxKeys = 2000;  // a parameter file has about a hundred; each unknown key costs a suggestion

// A quoted scalar ("10") or an explicit !!str: a string, never a number.
bool isQuoted(const YAML::Node& scalar) { return scalar.Tag() == "!" || scalar.Tag() == "tag:yaml.org,2002:str"; }

bool isText(const std::string& text) {
  return text.size() <= kMaxTextChars && text.find_first_not_of(kTextChars) == std::string::npos;
}

// Map keys in the document, counted up to `limit` + 1.
std::size_t countKeys(const YAML::Node& node, std::size_t limit) {
  std::size_t n = 0;
  for (const auto& item : node) {
    if (node.IsMap() && ++n > limit) return n;
    const YAML::Node& child = node.IsMap() ? item.second : static_cast<const YAML::Node&>(item);
    n += countKeys(child, limit - n);
    if (n > limit) return n;
  }
  return n;
}

std::string trim(const std::string& text) {
  const auto space = [](char c) { return std::isspace(static_cast<unsigned char>(c)) != 0; };
  const auto begin = std::find_if_not(text.begin(), text.end(), space);
  const auto end = std::find_if_not(text.rbegin(), text.rend(), space).base();
  return begin < end ? std::string(begin, end) : std::string();
}

// One parameter value as a file or a --set gave it, before it is checked. Never assigned: assigning a YAML::Node
// writes through to the node it refers to (the document), so entries live in a std::list.
struct Entry {
  std::string key;      // canonical (aliases resolved)
  std::string written;  // as the user wrote it; messages use this name
  YAML::Node value;
  std::string where;    // " (line L, column C)", " (from --set k=v)" or ""
  bool from_file = false;

  Entry(std::string k, std::string w, const YAML::Node& v, std::string at, bool file)
      : key(std::move(k)), written(std::move(w)), value(v), where(std::move(at)), from_file(file) {}
  Entry(const Entry&) = default;
  Entry& operator=(const Entry&) = delete;
};

class Reader {
 public:
  Reader(const Schema& schema, Values values) : schema_(schema), values_(std::move(values)) {}

  void problem(std::string message) { problems_.push_back(std::move(message)); }

  // A YAML document (the whole text). Returns false if it could not be read as a parameter file at all.
  bool readDocument(const std::string& text) {
    std::vector<YAML::Node> documents;
    try {
      documents = YAML::LoadAll(text);
    } catch (const YAML::Exception& e) {
      problem("invalid YAML" +
              (e.mark.is_null() ? std::string()
                                : " at line " + std::to_string(e.mark.line + 1) + ", column " +
                                      std::to_string(e.mark.column + 1)) +
              ": " + e.msg);
      return false;
    }
    if (documents.size() > 1) {
      problem("contains " + std::to_string(documents.size()) + " YAML documents; expected one");
      return false;
    }
    if (documents.empty() || documents.front().IsNull()) return true;
    const YAML::Node& root = documents.front();
    if (countKeys(root, kMaxKeys) > kMaxKeys) {
      problem("has more than " + std::to_string(kMaxKeys) + " keys: not a " + schema_.file_kind + " file");
      return false;
    }
    if (!root.IsMap()) {
      problem("the top level must be a map of parameters (e.g. '" + schema_.top_level_example + "'), got " +
              nodeKindName(root) + locationOf(root));
      return false;
    }
    std::set<std::string> seen;
    flatten(root, "", seen);
    return true;
  }

  // The --set arguments replace (or add) entries; a later one wins.
  void readOverrides(const std::vector<std::string>& overrides) {
    for (const std::string& text : overrides) {
      const std::string where = " (from --set " + text + ")";
      const auto eq = text.find('=');
      const std::string key = eq == std::string::npos ? std::string() : trim(text.substr(0, eq));
      if (key.empty()) {
        problem("malformed override '" + text + "'; expected key=value, e.g. --set " + schema_.override_example);
      } else if (!isLeaf(key)) {
        problem(isSection(key) ? "'" + key + "' is a group of parameters, not a parameter; set one of them, e.g. '" +
                                     firstLeafUnder(key) + "'" + where
                               : unknownKey(key) + where);
      } else {
        const std::string canonical = canonicalKey(key);
        entries_.remove_if([&](const Entry& e) { return e.key == canonical; });
        const std::string value_text = text.substr(eq + 1);
        try {
          entries_.emplace_back(canonical, key, YAML::Load(value_text), where, false);
        } catch (const YAML::Exception& e) {
          bad(canonical, key + " = '" + value_text + "' is not a valid YAML value: " + e.msg + where);
        }
      }
    }
  }

  void assignAll() {
    for (const Entry& e : entries_) {
      if (std::optional<Value> v = read(*schema_.find(e.key), e)) values_[e.key] = std::move(*v);
    }
    for (const Derived& d : schema_.derived) {
      if (findEntry(d.key) != nullptr || bad_.count(d.source) > 0) continue;
      names_[d.key] = d.key + " (= " + d.source + ")";
      values_[d.key] = values_.at(d.source);
      const Spec& spec = *schema_.find(d.key);
      const std::string& name = names_[d.key];
      if (auto p = numberProblem(spec, number(values_, d.key), name, plainValue(spec, values_[d.key]))) bad(d.key, *p);
    }
  }

  void checkRules(bool trust_file = false) {
    for (const Relation& r : schema_.relations) {
      if (bad_.count(r.lhs) > 0 || bad_.count(r.rhs) > 0) continue;
      const double a = number(values_, r.lhs);
      const double b = number(values_, r.rhs);
      if (r.strict ? a < b : a <= b) continue;
      problem(nameOf(r.lhs) + " = " + plainValue(*schema_.find(r.lhs), values_[r.lhs]) + " must be " +
              (r.strict ? "<" : "<=") + " " + nameOf(r.rhs) + " = " + plainValue(*schema_.find(r.rhs), values_[r.rhs]) +
              ": " + r.why);
    }
    checkApplies(trust_file);
    for (const Check& c : schema_.checks) {
      if (std::none_of(c.keys.begin(), c.keys.end(), [&](const std::string& k) { return bad_.count(k) > 0; })) {
        c.run(values_, problems_);
      }
    }
  }

  // A key given while a choice it depends on turns it off changes nothing: the user meant something else. A file's
  // key that --set turned off is fine (a sweep over the rule, a comparison run), and so is any key of a file a
  // program wrote (`trust_file`: an older dump wrote them all). Among --sets the order does not matter: a grid
  // point's values come together.
  void checkApplies(bool trust_file) {
    for (const Entry& e : entries_) {
      if (bad_.count(e.key) > 0 || (trust_file && e.from_file)) continue;
      for (const Applies& a : schema_.applies) {
        if (a.key != e.key || !turnsOff(a, values_) || bad_.count(a.when) > 0) continue;
        const Entry* when = findEntry(a.when);
        if (e.from_file && when != nullptr && !when->from_file) continue;
        problem(e.written + " applies to " + a.what + " only (" + nameOf(a.when) + " is " +
                plainValue(*schema_.find(a.when), values_.at(a.when)) + "); remove it or set " + nameOf(a.when) +
                e.where);
        break;  // one problem per key: the first rule that turns it off
      }
    }
  }

  // Values built in code: each against its bounds.
  void checkValues() {
    for (const Spec& s : schema_.specs) {
      const Value& v = values_.at(s.key);
      if (s.kind == Kind::kChoice && std::get<std::string>(v).empty()) {
        bad(s.key, s.key + " holds a value that is not one of: " + join(s.choices, ", "));
      } else if (s.kind == Kind::kText && !isText(std::get<std::string>(v))) {
        bad(s.key, s.key + " holds '" + std::get<std::string>(v) + "'; expected " + expectation(s));
      } else if (s.kind == Kind::kReal || s.kind == Kind::kInteger) {
        if (auto p = numberProblem(s, std::get<double>(v), s.key, plainValue(s, v))) bad(s.key, *p);
      }
    }
  }

  Values take(const std::string& source) {
    if (!problems_.empty()) throw ConfigError(source, std::move(problems_));
    return std::move(values_);
  }

 private:
  void bad(const std::string& key, std::string message) {
    bad_.insert(key);
    problem(std::move(message));
  }

  std::string nameOf(const std::string& key) const {
    if (const auto it = names_.find(key); it != names_.end()) return it->second;
    for (const Entry& e : entries_) {
      if (e.key == key) return e.written;
    }
    return key;
  }

  bool isLeaf(const std::string& key) const {
    return schema_.find(key) != nullptr ||
           std::any_of(schema_.aliases.begin(), schema_.aliases.end(), [&](const Alias& a) { return a.alias == key; });
  }

  bool isSection(const std::string& key) const { return !firstLeafUnder(key).empty(); }
  bool isForeign(const std::string& name) const {
    const auto& foreign = schema_.foreign_sections;
    return std::find(foreign.begin(), foreign.end(), name) != foreign.end();
  }

  std::string firstLeafUnder(const std::string& section) const {
    for (const Spec& s : schema_.specs) {
      if (startsWith(s.key, section + ".")) return s.key;
    }
    return {};
  }

  std::string canonicalKey(const std::string& key) const {
    for (const Alias& a : schema_.aliases) {
      if (a.alias == key) return a.key;
    }
    return key;
  }

  const Entry* findEntry(const std::string& key) const {
    for (const Entry& e : entries_) {
      if (e.key == key) return &e;
    }
    return nullptr;
  }

  std::string unknownKey(const std::string& key) const {
    std::string best;
    // A parameter of a mounted section written outside it (the scenario's "mode" for "agent.mode")?
    for (const auto& mount : schema_.mounts) {
      const std::string inside = mount.first + "." + key;
      if (!startsWith(key, mount.first + ".") && (isLeaf(inside) || isSection(inside))) best = inside;
    }
    std::vector<std::string> leaves;
    for (const Spec& s : schema_.specs) leaves.push_back(s.key);
    for (const Alias& a : schema_.aliases) leaves.push_back(a.alias);
    if (best.empty()) {
      std::vector<std::string> candidates = leaves;
      for (const std::string& leaf : leaves) {
        for (auto dot = leaf.find('.'); dot != std::string::npos; dot = leaf.find('.', dot + 1)) {
          candidates.push_back(leaf.substr(0, dot));
        }
      }
      best = closestMatch(key, candidates);
    }
    if (best.empty()) best = sameLeafMatch(key, leaves);  // right name, wrong section ("imu.gust_std")?
    return "unknown key '" + key + "'" + didYouMean(best);
  }

  // Walks a YAML map whose keys live under `prefix` ("" for the top level) into entries.
  void flatten(const YAML::Node& map, const std::string& prefix, std::set<std::string>& seen) {
    for (const auto& item : map) {
      const YAML::Node& key_node = item.first;
      const YAML::Node& value = item.second;
      if (!key_node.IsScalar()) {
        problem("a key " + (prefix.empty() ? std::string("at the top level") : "under '" + prefix + "'") + " is " +
                nodeKindName(key_node) + ", not a name" + locationOf(key_node));
        continue;
      }
      const std::string& name = key_node.Scalar();
      const std::string key = prefix.empty() ? name : prefix + "." + name;
      if (prefix.empty() && isForeign(name)) continue;
      if (!seen.insert(key).second) {
        bad(canonicalKey(key), "duplicate key '" + key + "'" + locationOf(key_node));
      } else if (name.find('.') != std::string::npos) {
        const auto dot = key.rfind('.');
        problem(isLeaf(key) || isSection(key)
                    ? "dotted key '" + key + "' must be written nested (a '" + key.substr(0, dot) + ":' map holding '" +
                          key.substr(dot + 1) + ":'); dotted keys are for --set" + locationOf(key_node)
                    : unknownKey(key) + locationOf(key_node));
      } else if (isLeaf(key)) {
        const std::string canonical = canonicalKey(key);
        if (const Entry* other = findEntry(canonical)) {
          const std::string alias = canonical == key ? other->written : key;
          bad(canonical, "'" + key + "' and '" + other->written + "' set the same parameter ('" + alias +
                             "' is a shortcut for '" + canonical + "'); give only one" + locationOf(key_node));
          continue;
        }
        const std::string where = locationOf(value).empty() ? locationOf(key_node) : locationOf(value);
        entries_.emplace_back(canonical, key, value, where, true);
      } else if (isSection(key)) {
        if (value.IsMap()) {
          flatten(value, key, seen);
        } else if (!value.IsNull()) {  // an empty section ("wind:") keeps the defaults
          problem("'" + key + "' must be a map of parameters, got " + nodeKindName(value) + locationOf(value));
        }
      } else {
        problem(unknownKey(key) + locationOf(key_node));
      }
    }
  }

  static std::optional<std::string> numberProblem(const Spec& s, double v, const std::string& name,
                                                  const std::string& shown) {
    if (s.allow_infinity && !std::isfinite(v)) {
      if (v == std::numeric_limits<double>::infinity()) return std::nullopt;
      return name + " = " + shown + " is not a finite number; expected " + expectation(s);
    }
    return params::numberProblem(name, v, shown, s.kind != Kind::kReal, s.range, rangeText(s) + unitSuffix(s));
  }

  // A plain scalar as a valid number for `s`, else nullopt and `fail` told why (`fail` returns std::nullopt).
  template <class Fail>
  static std::optional<double> readNumber(const Spec& s, const YAML::Node& value, const std::string& name,
                                          const Fail& fail) {
    if (!value.IsScalar()) return fail(name + " must be " + expectation(s) + ", got " + nodeKindName(value));
    const std::string& text = value.Scalar();
    if (isQuoted(value)) return fail(name + " = \"" + text + "\" is a string; expected " + expectation(s));
    double number = 0.0;
    switch (parseNumber(text, number)) {
      case NumberStatus::kNotANumber:
        return fail(name + " = '" + text + "' is not a number; expected " + expectation(s));
      case NumberStatus::kUnrepresentable:
        return fail(name + " = " + text + " cannot be represented as a double");
      case NumberStatus::kOk:
        break;
    }
    if (auto why = numberProblem(s, number, name, text)) return fail(std::move(*why));
    return number;
  }

  // The value of entry `e` for parameter `s`, or nullopt after reporting why it is not valid.
  std::optional<Value> read(const Spec& s, const Entry& e) {
    const std::string& name = e.written;
    const auto fail = [&](std::string message) {
      bad(s.key, std::move(message) + e.where);
      return std::nullopt;
    };
    const YAML::Node& value = e.value;
    if (value.IsNull()) return fail(name + " has no value; expected " + expectation(s));
    if (s.kind == Kind::kIntList || s.kind == Kind::kRecordList) {
      if (!value.IsSequence()) {
        return fail(name + " must be " + expectation(s) + ", got " + nodeKindName(value));
      }
      return s.kind == Kind::kIntList ? readIntList(s, e) : readRecords(s, e);
    }
    if (!value.IsScalar()) return fail(name + " must be " + expectation(s) + ", got " + nodeKindName(value));
    const std::string& text = value.Scalar();
    switch (s.kind) {
      case Kind::kChoice:
        if (std::find(s.choices.begin(), s.choices.end(), text) != s.choices.end()) return Value(text);
        return fail(name + " = '" + text + "' is not valid; expected " + expectation(s));
      case Kind::kText:
        if (isText(text)) return Value(text);
        return fail(name + " = '" + text.substr(0, 80) + "' is not valid; expected " + expectation(s));
      case Kind::kBool:
        if (isQuoted(value)) return fail(name + " = \"" + text + "\" is a string; expected true or false");
        if (text == "true" || text == "True" || text == "TRUE") return Value(true);
        if (text == "false" || text == "False" || text == "FALSE") return Value(false);
        return fail(name + " = '" + text + "' is not valid; expected true or false");
      case Kind::kSeed:
        if (isQuoted(value)) return fail(name + " = \"" + text + "\" is a string; expected " + expectation(s));
        return readSeed(s, name, text, fail);
      default:
        if (const auto v = readNumber(s, value, name, fail)) return Value(*v);
        return std::nullopt;
    }
  }

  template <class Fail>
  static std::optional<Value> readSeed(const Spec& s, const std::string& name, const std::string& text,
                                       const Fail& fail) {
    std::string_view digits = text;
    if (!digits.empty() && digits.front() == '+') digits.remove_prefix(1);
    const bool negative = !digits.empty() && digits.front() == '-';
    if (negative) digits.remove_prefix(1);
    const bool all_digits = !digits.empty() && std::all_of(digits.begin(), digits.end(), [](char c) {
      return c >= '0' && c <= '9';
    });
    if (!all_digits) return fail(name + " = '" + text + "' is not " + expectation(s));
    std::uint64_t seed = 0;
    const auto [ptr, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), seed);
    if (negative || ec != std::errc() || ptr != digits.data() + digits.size()) {
      return fail(name + " = " + text + " is out of range " + rangeText(s));
    }
    return Value(seed);
  }

  // Where a problem inside a list element is: the element's own line in a file, the --set otherwise.
  static std::string whereIn(const Entry& e, const YAML::Node& at) {
    return e.from_file && !locationOf(at).empty() ? locationOf(at) : e.where;
  }

  std::optional<Value> readIntList(const Spec& s, const Entry& e) {
    std::vector<long long> list;
    bool ok = true;
    Spec element = s;
    element.kind = Kind::kInteger;
    for (const YAML::Node& item : e.value) {
      const auto fail = [&](std::string message) {
        ok = false;
        bad(s.key, std::move(message) + whereIn(e, item));
        return std::nullopt;
      };
      const std::string name = e.written + "[" + std::to_string(list.size()) + "]";
      if (const auto v = readNumber(element, item, name, fail)) list.push_back(static_cast<long long>(*v));
      else list.push_back(0);  // keeps the next element's index
    }
    return ok ? std::optional<Value>(list) : std::nullopt;
  }

  std::optional<Value> readRecords(const Spec& s, const Entry& e) {
    std::vector<Record> records;
    bool ok = true;
    for (const YAML::Node& item : e.value) {
      const std::string name = e.written + "[" + std::to_string(records.size()) + "]";
      const auto fail = [&](std::string message, const YAML::Node& at) {
        ok = false;
        bad(s.key, std::move(message) + whereIn(e, at));
      };
      records.push_back(readRecord(s, item, name, fail));
    }
    return ok ? std::optional<Value>(records) : std::nullopt;
  }

  // One element of a record list: a map of the spec's fields. Every problem goes to `fail`.
  template <class Fail>
  static Record readRecord(const Spec& s, const YAML::Node& item, const std::string& name, const Fail& fail) {
    Record record(s.fields.size(), 0.0);
    std::vector<std::string> names;
    for (const Spec& f : s.fields) names.push_back(f.key);
    if (!item.IsMap()) {
      fail(name + " must be a map such as " + s.example + ", got " + nodeKindName(item), item);
      return record;
    }
    std::vector<const YAML::Node*> given(s.fields.size(), nullptr);
    std::vector<bool> valid(s.fields.size(), false);
    std::list<YAML::Node> nodes;  // copies: a YAML::Node is never assigned
    for (const auto& field : item) {
      if (!field.first.IsScalar()) {
        fail("a key in " + name + " is " + nodeKindName(field.first) + ", not a name; expected " + join(names, ", "),
             field.first);
        continue;
      }
      const std::string& key = field.first.Scalar();
      const auto at = std::find(names.begin(), names.end(), key);
      if (at == names.end()) {
        fail("unknown key '" + key + "' in " + name + didYouMean(closestMatch(key, names)) + "; expected " +
                 join(names, ", "),
             field.first);
        continue;
      }
      const auto i = static_cast<std::size_t>(at - names.begin());
      if (given[i] != nullptr) {
        fail("duplicate key '" + name + "." + key + "'", field.first);
        continue;
      }
      given[i] = &nodes.emplace_back(field.second);
      const auto field_fail = [&](std::string message) {
        fail(std::move(message), field.second);
        return std::nullopt;
      };
      if (const auto v = readNumber(s.fields[i], field.second, name + "." + key, field_fail)) {
        record[i] = *v;
        valid[i] = true;
      }
    }
    for (std::size_t i = 0; i < s.fields.size(); ++i) {
      if (given[i] != nullptr) continue;
      if (s.fields[i].default_value) {
        record[i] = *s.fields[i].default_value;
        valid[i] = true;
      } else {
        fail(name + " has no " + names[i] + "; expected a map such as " + s.example, item);
      }
    }
    const auto index = [&](const std::string& field) {
      return static_cast<std::size_t>(std::find(names.begin(), names.end(), field) - names.begin());
    };
    const std::size_t earlier = index(s.earlier);
    const std::size_t later = index(s.later);
    if (later < names.size() && valid[earlier] && valid[later] && given[later] != nullptr &&
        !(record[later] > record[earlier])) {
      const std::string unit = unitSuffix(s.fields[later]);
      fail(name + "." + s.later + " = " + formatYamlNumber(record[later]) + unit + " must be > " + name + "." +
               s.earlier + " = " + formatYamlNumber(record[earlier]) + unit + ": " + s.order_why,
           *given[later]);
    }
    return record;
  }

  const Schema& schema_;
  Values values_;
  std::list<Entry> entries_;
  std::map<std::string, std::string> names_;  // derived keys: "key (= source)"
  std::set<std::string> bad_;                 // keys whose own value is invalid: rules over them are not judged
  std::vector<std::string> problems_;
};

Values read(const Schema& schema, Values values, const std::string* text, std::string unreadable,
            const std::string& source, const std::vector<std::string>& overrides, bool trust_file = false) {
  Reader reader(schema, std::move(values));
  bool file_ok = text != nullptr;
  if (!file_ok) reader.problem(std::move(unreadable));
  if (text != nullptr) file_ok = reader.readDocument(*text);
  reader.readOverrides(overrides);
  reader.assignAll();
  // Rules over a file that could not be read would judge defaults the file may have changed.
  if (file_ok) reader.checkRules(trust_file);
  return reader.take(source);
}

}  // namespace

Values loadFile(const Schema& schema, Values values, const std::string& path,
                const std::vector<std::string>& overrides) {
  std::string problem;
  const std::optional<std::string> text = readTextFile(path, schema.file_kind, problem);
  return read(schema, std::move(values), text ? &*text : nullptr, problem, path, overrides);
}

Values parseText(const Schema& schema, Values values, const std::string& text, const std::string& source,
                 const std::vector<std::string>& overrides) {
  return read(schema, std::move(values), &text, {}, source, overrides);
}

Values parseDump(const Schema& schema, Values values, const std::string& text, const std::string& source,
                 const std::vector<std::string>& overrides) {
  return read(schema, std::move(values), &text, {}, source, overrides, /*trust_file=*/true);
}

void validate(const Schema& schema, const Values& values, const std::string& source) {
  Reader reader(schema, values);
  reader.checkValues();
  reader.checkRules();
  reader.take(source);
}

}  // namespace swa::params

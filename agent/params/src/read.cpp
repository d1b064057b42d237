// Reading parameters: a YAML file and --set overrides become flat entries (key, value node, where it was written),
// each entry is checked against its Spec into a Value, then the rules between parameters are judged. Every problem
// is collected; the first one does not hide the others.

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cctype>
#include <list>
#include <set>

#include "read_value.h"
#include "spec_text.h"
#include "swa/params/engine.h"
#include "swa/params/file.h"
#include "yaml_error.h"
#include "yaml_node.h"

namespace swa::params {

namespace {

using namespace detail;

constexpr std::size_t kMaxKeys = 2000;  // a parameter file has about a hundred; each unknown key costs a suggestion

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
  std::string where;  // " (line L, column C)", " (from --set k=v)" or ""
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
      problem(detail::yamlErrorText(e, text));
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
      if (!std::holds_alternative<double>(values_[d.key])) continue;  // a choice: the source's own values are valid
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
    for (const Alias& a : schema_.aliases) {  // a section of aliases only (the scenario's mission:)
      if (startsWith(a.alias, section + ".")) return a.key;
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

  // The value of entry `e` for parameter `s`, or nullopt after reporting why it is not valid.
  std::optional<Value> read(const Spec& s, const Entry& e) {
    return readValue(s, e.value, e.written, [&](std::string message, const YAML::Node* at) {
      // A list element's problem is at the element's own line in a file; the --set otherwise.
      const bool own_line = at != nullptr && e.from_file && !locationOf(*at).empty();
      bad(s.key, std::move(message) + (own_line ? locationOf(*at) : e.where));
    });
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

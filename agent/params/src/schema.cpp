#include "swa/params/schema.h"

#include <algorithm>

#include "swa/params/error.h"
#include "swa/params/file.h"

namespace swa::params {

namespace {

std::string joinWithSource(const std::string& source, const std::vector<std::string>& problems) {
  std::string text;
  for (const std::string& problem : problems) text += (text.empty() ? "" : "\n") + source + ": " + problem;
  return text;
}

}  // namespace

ConfigError::ConfigError(std::string source, std::vector<std::string> problems)
    : ConfigError(Summarised{}, std::move(source), summariseProblems(problems)) {}

ConfigError::ConfigError(Summarised, std::string source, std::vector<std::string> problems)
    : std::runtime_error(joinWithSource(source, problems)),
      source_(std::move(source)),
      problems_(std::move(problems)) {}

const Spec* Schema::find(const std::string& key) const {
  for (const Spec& s : specs) {
    if (s.key == key) return &s;
  }
  return nullptr;
}

bool turnsOff(const Applies& a, const Values& values) {
  const Value& when = values.at(a.when);
  if (const auto* chosen = std::get_if<std::string>(&when)) {
    if (a.values.empty()) return chosen->empty();  // a text: off while empty
    return std::find(a.values.begin(), a.values.end(), *chosen) == a.values.end();
  }
  const auto* number = std::get_if<double>(&when);
  return number != nullptr && a.values.empty() && *number == 0.0;
}

const Applies* Schema::unused(const std::string& key, const Values& values) const {
  for (const Applies& a : applies) {
    if (a.key == key && turnsOff(a, values)) return &a;
  }
  return nullptr;
}

void Schema::mount(const std::string& prefix, const Schema& inner, const std::string& comment) {
  const std::string p = prefix + ".";
  for (Spec s : inner.specs) {
    s.key = p + s.key;
    specs.push_back(std::move(s));
  }
  for (const Relation& r : inner.relations) relations.push_back({p + r.lhs, r.strict, p + r.rhs, r.why});
  for (const Applies& a : inner.applies) applies.push_back({p + a.key, p + a.when, a.values, a.what});
  for (const Alias& a : inner.aliases) aliases.push_back({p + a.alias, p + a.key});
  for (const Derived& d : inner.derived) derived.push_back({p + d.key, p + d.source});
  mounts[prefix] = comment;
}

double number(const Values& values, const std::string& key) { return std::get<double>(values.at(key)); }

const std::vector<long long>& intList(const Values& values, const std::string& key) {
  return std::get<std::vector<long long>>(values.at(key));
}

std::size_t recordSlot(const Spec& s, std::size_t field) {
  std::size_t slot = 0;
  for (std::size_t i = 0; i < field && i < s.fields.size(); ++i) slot += s.fields[i].components;
  return slot;
}

std::size_t recordSlots(const Spec& s) { return recordSlot(s, s.fields.size()); }

const std::vector<Record>& records(const Values& values, const std::string& key) {
  return std::get<std::vector<Record>>(values.at(key));
}

}  // namespace swa::params

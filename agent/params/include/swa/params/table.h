#pragma once
// A Schema bound to the struct it fills: each parameter is declared once with an accessor to its field, and the
// engine's reading, validation, dump and description then work on that struct directly.
//
//   Table<AgentConfig> t("SWA agent configuration", "configuration", "formation:", "formation.radius_m=12");
//   SWA_PARAM(t, number, formation.radius_m, "m", openClosed(0, 1000), "r: desired distance to the neighbours");
//
// SWA_PARAM spells the key as the field's path, so a key cannot drift from its field; an accessor is a generic
// lambda returning a reference to the field, so it serves const and mutable structs.

#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "swa/params/engine.h"
#include "swa/params/schema.h"

// Declares the parameter `path` (a member path of the table's struct, e.g. formation.radius_m) with Table::`kind`;
// the remaining arguments are those of `kind` after the key and the accessor.
#define SWA_PARAM(table, kind, path, ...) \
  (table).kind(                           \
      #path, [](auto& x) -> auto& { return x.path; }, __VA_ARGS__)

namespace swa::params {

template <class T>
class Table {
 public:
  using Get = std::function<Value(const T&)>;
  using Set = std::function<void(T&, const Value&)>;

  // The schema's wording: see Schema.
  Table(std::string title, std::string file_kind, std::string top_level_example, std::string override_example,
        std::string notes = "") {
    schema_.title = std::move(title);
    schema_.file_kind = std::move(file_kind);
    schema_.top_level_example = std::move(top_level_example);
    schema_.override_example = std::move(override_example);
    schema_.notes = std::move(notes);
  }

  const Schema& schema() const { return schema_; }
  Schema& schema() { return schema_; }

  void add(Spec spec, Get get, Set set) {
    schema_.specs.push_back(std::move(spec));
    get_.push_back(std::move(get));
    set_.push_back(std::move(set));
  }

  // A real or an integer, by the field's type.
  template <class Access>
  void number(std::string key, Access access, std::string unit, Range range, std::string meaning,
              bool allow_infinity = false) {
    using Field = std::decay_t<decltype(access(std::declval<T&>()))>;
    static_assert(std::is_arithmetic_v<Field> && !std::is_same_v<Field, bool>);
    Spec s = makeSpec(std::move(key), std::is_integral_v<Field> ? Kind::kInteger : Kind::kReal, std::move(unit), range);
    s.allow_infinity = allow_infinity;
    s.meaning = std::move(meaning);
    add(
        std::move(s), [access](const T& t) { return Value(static_cast<double>(access(t))); },
        [access](T& t, const Value& v) { access(t) = static_cast<Field>(std::get<double>(v)); });
  }

  template <class Access, class Enum>
  void choice(std::string key, Access access, std::vector<std::pair<Enum, std::string>> names, std::string meaning) {
    Spec s = makeSpec(std::move(key), Kind::kChoice);
    for (const auto& n : names) s.choices.push_back(n.second);
    s.meaning = std::move(meaning);
    add(
        std::move(s),
        [access, names](const T& t) {
          for (const auto& n : names) {
            if (n.first == access(t)) return Value(n.second);
          }
          return Value(std::string());  // not a listed value: validate() says so
        },
        [access, names](T& t, const Value& v) {
          for (const auto& n : names) {
            if (n.second == std::get<std::string>(v)) access(t) = n.first;
          }
        });
  }

  // Free text within kTextChars (a frame id, a list of class names); `expected` words it in messages.
  template <class Access>
  void text(std::string key, Access access, std::string meaning, std::string expected) {
    Spec s = makeSpec(std::move(key), Kind::kText);
    s.meaning = std::move(meaning);
    s.expected = std::move(expected);
    add(
        std::move(s), [access](const T& t) { return Value(std::string(access(t))); },
        [access](T& t, const Value& v) { access(t) = std::get<std::string>(v); });
  }

  template <class Access>
  void flag(std::string key, Access access, std::string meaning) {
    Spec s = makeSpec(std::move(key), Kind::kBool);
    s.choices = {"true", "false"};
    s.meaning = std::move(meaning);
    add(
        std::move(s), [access](const T& t) { return Value(static_cast<bool>(access(t))); },
        [access](T& t, const Value& v) { access(t) = std::get<bool>(v); });
  }

  template <class Access>
  void seed(std::string key, Access access, std::string meaning) {
    Spec s = makeSpec(std::move(key), Kind::kSeed);
    s.meaning = std::move(meaning);
    add(
        std::move(s), [access](const T& t) { return Value(static_cast<std::uint64_t>(access(t))); },
        [access](T& t, const Value& v) { access(t) = std::get<std::uint64_t>(v); });
  }

  // A list of integers, each within `element_range`; `expected` and `comment` word it in messages and the dump.
  template <class Access>
  void intList(std::string key, Access access, Range element_range, std::string meaning, std::string expected,
               std::string comment) {
    Spec s = makeSpec(std::move(key), Kind::kIntList, "", element_range);
    s.meaning = std::move(meaning);
    s.expected = std::move(expected);
    s.comment = std::move(comment);
    add(
        std::move(s),
        [access](const T& t) {
          const auto& list = access(t);
          return Value(std::vector<long long>(list.begin(), list.end()));
        },
        [access](T& t, const Value& v) {
          const auto& list = std::get<std::vector<long long>>(v);
          access(t).assign(list.begin(), list.end());
        });
  }

  // Every parameter and rule of `inner` under "prefix.", reached through `access` (a generic lambda returning the
  // inner struct).
  template <class U, class Access>
  void mount(const std::string& prefix, const Table<U>& inner, Access access, const std::string& comment) {
    schema_.mount(prefix, inner.schema(), comment);
    for (std::size_t i = 0; i < inner.get_.size(); ++i) {
      get_.push_back([access, get = inner.get_[i]](const T& t) { return get(access(t)); });
      set_.push_back([access, set = inner.set_[i]](T& t, const Value& v) { set(access(t), v); });
    }
  }

  Values values(const T& t) const {
    Values out;
    for (std::size_t i = 0; i < get_.size(); ++i) out.emplace(schema_.specs[i].key, get_[i](t));
    return out;
  }

  T build(const Values& values, T t = T{}) const {
    for (std::size_t i = 0; i < set_.size(); ++i) set_[i](t, values.at(schema_.specs[i].key));
    return t;
  }

  T load(const std::string& path, const std::vector<std::string>& overrides = {}) const {
    return build(loadFile(schema_, values(T{}), path, overrides));
  }
  T parse(const std::string& text, const std::string& source, const std::vector<std::string>& overrides = {}) const {
    return build(parseText(schema_, values(T{}), text, source, overrides));
  }
  T parseDump(const std::string& text, const std::string& source,
              const std::vector<std::string>& overrides = {}) const {
    return build(params::parseDump(schema_, values(T{}), text, source, overrides));
  }
  // `overrides` on top of `base`; ConfigError with source "--set".
  T override(const T& base, const std::vector<std::string>& overrides) const {
    return build(parseText(schema_, values(base), "", "--set", overrides), base);
  }
  void validate(const T& t, const std::string& source) const { params::validate(schema_, values(t), source); }
  std::string dump(const T& t) const { return params::dump(schema_, values(t)); }
  std::string describe() const { return params::describe(schema_, values(T{})); }

 private:
  template <class>
  friend class Table;

  Schema schema_;
  std::vector<Get> get_;  // parallel to schema_.specs
  std::vector<Set> set_;
};

}  // namespace swa::params

#pragma once
// A small JSON document model for the files the monitor writes and reads back (summary.json of a run, the combined
// summary.json): parse, look up, build, print. Not a general-purpose library, but a strict parser of RFC 8259 JSON
// (no comments, no trailing commas, \uXXXX escapes incl. surrogate pairs to UTF-8) that reports where it failed.
//
// Numbers keep their source text, so a value read and printed again is byte-identical (a 64-bit seed survives);
// number() converts on demand. Object members keep their order; a repeated key is a parse error.

#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace swa::monitor_node {

class JsonError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class JsonValue {
 public:
  enum class Type { kNull, kBool, kNumber, kString, kArray, kObject };

  JsonValue() = default;  // null
  static JsonValue boolean(bool value);
  static JsonValue number(double value);  // null when not finite (JSON has no NaN)
  static JsonValue integer(std::int64_t value);
  static JsonValue unsignedInteger(std::uint64_t value);
  static JsonValue string(std::string value);
  static JsonValue array();
  static JsonValue object();

  // Throws JsonError "line L, column C: what" on malformed text or trailing garbage.
  static JsonValue parse(std::string_view text);

  Type type() const { return type_; }
  bool isNull() const { return type_ == Type::kNull; }
  bool isObject() const { return type_ == Type::kObject; }
  bool isArray() const { return type_ == Type::kArray; }

  // Typed reads: nullopt when the value has another type (null included: a reader decides what null means).
  std::optional<bool> asBool() const;
  std::optional<double> asNumber() const;
  std::optional<std::string> asString() const;
  // A number whose text is an integer in range; nullopt otherwise (e.g. 1.5, 1e3, null).
  std::optional<std::int64_t> asInteger() const;
  std::optional<std::uint64_t> asUnsigned() const;

  // Object members and array items (empty for other types).
  const std::vector<std::pair<std::string, JsonValue>>& members() const { return members_; }
  const std::vector<JsonValue>& items() const { return items_; }
  // The member `key` of an object; nullptr when absent or not an object.
  const JsonValue* find(std::string_view key) const;

  // Building. set() replaces an existing member in place (keeping its position) or appends.
  JsonValue& set(const std::string& key, JsonValue value);
  JsonValue& push(JsonValue value);

  // Two-space indented text ending in a newline at top level; a container holding no container is printed on one
  // line (so a list of events is one event per line).
  std::string dump() const;

 private:
  friend class JsonParser;
  void dumpTo(std::string& out, int depth) const;
  bool flat() const;

  Type type_ = Type::kNull;
  bool bool_ = false;
  std::string text_;  // string value, or the number's source text
  std::vector<JsonValue> items_;
  std::vector<std::pair<std::string, JsonValue>> members_;
};

}  // namespace swa::monitor_node

#include "read_value.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <list>
#include <string_view>
#include <vector>

#include "spec_text.h"
#include "swa/params/engine.h"
#include "swa/params/file.h"
#include "yaml_node.h"

namespace swa::params::detail {

namespace {

// A quoted scalar ("10") or an explicit !!str: a string, never a number.
bool isQuoted(const YAML::Node& scalar) { return scalar.Tag() == "!" || scalar.Tag() == "tag:yaml.org,2002:str"; }

// A plain scalar as a valid number for `s`, else nullopt and `fail` told why.
std::optional<double> readNumber(const Spec& s, const YAML::Node& value, const std::string& name,
                                 const std::function<void(std::string)>& fail) {
  const auto failed = [&](std::string message) {
    fail(std::move(message));
    return std::nullopt;
  };
  if (!value.IsScalar()) return failed(name + " must be " + expectation(s) + ", got " + nodeKindName(value));
  const std::string& text = value.Scalar();
  if (isQuoted(value)) return failed(name + " = \"" + text + "\" is a string; expected " + expectation(s));
  double number = 0.0;
  switch (parseNumber(text, number)) {
    case NumberStatus::kNotANumber:
      return failed(name + " = '" + text + "' is not a number; expected " + expectation(s));
    case NumberStatus::kUnrepresentable:
      return failed(name + " = " + text + " cannot be represented as a double");
    case NumberStatus::kOk:
      break;
  }
  if (auto why = numberProblem(s, number, name, text)) return failed(std::move(*why));
  return number;
}

std::optional<Value> readSeed(const Spec& s, const std::string& name, const std::string& text,
                              const std::function<void(std::string)>& fail) {
  std::string_view digits = text;
  if (!digits.empty() && digits.front() == '+') digits.remove_prefix(1);
  const bool negative = !digits.empty() && digits.front() == '-';
  if (negative) digits.remove_prefix(1);
  const bool all_digits =
      !digits.empty() && std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; });
  if (!all_digits) {
    fail(name + " = '" + text + "' is not " + expectation(s));
    return std::nullopt;
  }
  std::uint64_t seed = 0;
  const auto [ptr, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), seed);
  if (negative || ec != std::errc() || ptr != digits.data() + digits.size()) {
    fail(name + " = " + text + " is out of range " + rangeText(s));
    return std::nullopt;
  }
  return Value(seed);
}

std::optional<Value> readIntList(const Spec& s, const YAML::Node& list_node, const std::string& name,
                                 const ValueFail& fail) {
  std::vector<long long> list;
  bool ok = true;
  Spec element = s;
  element.kind = Kind::kInteger;
  for (const YAML::Node& item : list_node) {
    const auto item_fail = [&](std::string message) {
      ok = false;
      fail(std::move(message), &item);
    };
    const std::string item_name = name + "[" + std::to_string(list.size()) + "]";
    if (const auto v = readNumber(element, item, item_name, item_fail))
      list.push_back(static_cast<long long>(*v));
    else
      list.push_back(0);  // keeps the next element's index
  }
  return ok ? std::optional<Value>(list) : std::nullopt;
}

// A field of `components` numbers: a list of exactly that many, each valid for the field. Problems go to `fail`.
bool readComponents(const Spec& f, const YAML::Node& value, const std::string& name, Record& record, std::size_t slot,
                    const std::function<void(std::string)>& fail) {
  const std::string expected = "a list of " + std::to_string(f.components) + " numbers" +
                               (f.unit.empty() ? std::string() : " in " + f.unit) + " such as [3, 0]";
  if (!value.IsSequence() || value.size() != f.components) {
    fail(name + " must be " + expected + ", got " +
         (value.IsSequence() ? "a list of " + std::to_string(value.size()) : nodeKindName(value)));
    return false;
  }
  bool ok = true;
  for (std::size_t j = 0; j < f.components; ++j) {
    const auto v = readNumber(f, value[j], name + "[" + std::to_string(j) + "]", fail);
    if (v) record[slot + j] = *v;
    ok = ok && v.has_value();
  }
  return ok;
}

// Which of the spec's forms the given fields make: its index, or nullopt with `fail` told why.
std::optional<std::size_t> formOf(const Spec& s, const std::vector<std::string>& names,
                                  const std::vector<const YAML::Node*>& given, const std::string& name,
                                  const std::function<void(std::string)>& fail) {
  const auto has = [&](const std::string& field) {
    const auto at = std::find(names.begin(), names.end(), field);
    return at != names.end() && given[static_cast<std::size_t>(at - names.begin())] != nullptr;
  };
  std::vector<std::string> forms;
  std::optional<std::size_t> complete;
  int started = 0;
  for (std::size_t k = 0; k < s.forms.size(); ++k) {
    const auto& form = s.forms[k];
    forms.push_back(join(form, " and "));
    const auto n = std::count_if(form.begin(), form.end(), has);
    if (n > 0) ++started;
    if (n == static_cast<long>(form.size()) && !complete) complete = k;
  }
  if (complete && started == 1) return complete;
  fail(name + (started > 1 ? " mixes two forms" : " is incomplete") + "; it gives either " + join(forms, ", or ") +
       " (such as " + s.example + ")");
  return std::nullopt;
}

// One element of a record list: a map of the spec's fields. Every problem goes to `fail`.
Record readRecord(const Spec& s, const YAML::Node& item, const std::string& name,
                  const std::function<void(std::string, const YAML::Node&)>& fail) {
  Record record(recordSlots(s), 0.0);
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
    const auto field_fail = [&](std::string message) { fail(std::move(message), field.second); };
    const Spec& f = s.fields[i];
    const std::size_t slot = recordSlot(s, i);
    if (f.components != 1) {
      valid[i] = readComponents(f, field.second, name + "." + key, record, slot, field_fail);
    } else if (const auto v = readNumber(f, field.second, name + "." + key, field_fail)) {
      record[slot] = *v;
      valid[i] = true;
    }
  }
  // The fields of the forms the element does not take hold NaN; a field outside every form is required as before.
  std::vector<bool> in_form(s.fields.size(), false);
  std::optional<std::size_t> form;
  if (!s.forms.empty()) {
    form = formOf(s, names, given, name, [&](std::string message) { fail(std::move(message), item); });
    if (!form) return record;
    for (const auto& f : s.forms) {
      for (const std::string& field : f) {
        const auto i = static_cast<std::size_t>(std::find(names.begin(), names.end(), field) - names.begin());
        if (i < names.size()) in_form[i] = true;
      }
    }
  }
  for (std::size_t i = 0; i < s.fields.size(); ++i) {
    if (given[i] != nullptr) continue;
    if (in_form[i]) {
      std::fill_n(record.begin() + static_cast<long>(recordSlot(s, i)), s.fields[i].components,
                  std::numeric_limits<double>::quiet_NaN());
    } else if (s.fields[i].default_value) {
      record[recordSlot(s, i)] = *s.fields[i].default_value;
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
      !(record[recordSlot(s, later)] > record[recordSlot(s, earlier)])) {
    const std::string unit = unitSuffix(s.fields[later]);
    fail(name + "." + s.later + " = " + formatYamlNumber(record[recordSlot(s, later)]) + unit + " must be > " + name +
             "." + s.earlier + " = " + formatYamlNumber(record[recordSlot(s, earlier)]) + unit + ": " + s.order_why,
         *given[later]);
  }
  return record;
}

std::optional<Value> readRecords(const Spec& s, const YAML::Node& list_node, const std::string& name,
                                 const ValueFail& fail) {
  std::vector<Record> records;
  bool ok = true;
  for (const YAML::Node& item : list_node) {
    const std::string item_name = name + "[" + std::to_string(records.size()) + "]";
    const auto item_fail = [&](std::string message, const YAML::Node& at) {
      ok = false;
      fail(std::move(message), &at);
    };
    records.push_back(readRecord(s, item, item_name, item_fail));
  }
  return ok ? std::optional<Value>(records) : std::nullopt;
}

}  // namespace

bool isText(const std::string& text) {
  return text.size() <= kMaxTextChars && text.find_first_not_of(kTextChars) == std::string::npos;
}

std::optional<std::string> numberProblem(const Spec& s, double v, const std::string& name, const std::string& shown) {
  if (s.allow_infinity && !std::isfinite(v)) {
    if (v == std::numeric_limits<double>::infinity()) return std::nullopt;
    return name + " = " + shown + " is not a finite number; expected " + expectation(s);
  }
  return params::numberProblem(name, v, shown, s.kind != Kind::kReal, s.range, rangeText(s) + unitSuffix(s));
}

std::optional<Value> readValue(const Spec& s, const YAML::Node& value, const std::string& name, const ValueFail& fail) {
  const auto failed = [&](std::string message) {
    fail(std::move(message), nullptr);
    return std::nullopt;
  };
  if (value.IsNull()) return failed(name + " has no value; expected " + expectation(s));
  if (s.kind == Kind::kIntList || s.kind == Kind::kRecordList) {
    if (!value.IsSequence()) return failed(name + " must be " + expectation(s) + ", got " + nodeKindName(value));
    return s.kind == Kind::kIntList ? readIntList(s, value, name, fail) : readRecords(s, value, name, fail);
  }
  if (!value.IsScalar()) return failed(name + " must be " + expectation(s) + ", got " + nodeKindName(value));
  const std::string& text = value.Scalar();
  const auto told = [&](std::string message) { fail(std::move(message), nullptr); };
  switch (s.kind) {
    case Kind::kChoice:
      if (std::find(s.choices.begin(), s.choices.end(), text) != s.choices.end()) return Value(text);
      return failed(name + " = '" + text + "' is not valid; expected " + expectation(s));
    case Kind::kText:
      if (isText(text)) return Value(text);
      return failed(name + " = '" + text.substr(0, 80) + "' is not valid; expected " + expectation(s));
    case Kind::kBool:
      if (isQuoted(value)) return failed(name + " = \"" + text + "\" is a string; expected true or false");
      if (text == "true" || text == "True" || text == "TRUE") return Value(true);
      if (text == "false" || text == "False" || text == "FALSE") return Value(false);
      return failed(name + " = '" + text + "' is not valid; expected true or false");
    case Kind::kSeed:
      if (isQuoted(value)) return failed(name + " = \"" + text + "\" is a string; expected " + expectation(s));
      return readSeed(s, name, text, told);
    default:
      if (const auto v = readNumber(s, value, name, told)) return Value(*v);
      return std::nullopt;
  }
}

}  // namespace swa::params::detail

// Writing parameters: the commented YAML dump and the --help description, and the wording they share with the
// messages of read.cpp.

#include <algorithm>
#include <cmath>
#include <limits>

#include "spec_text.h"
#include "swa/params/engine.h"

namespace swa::params {

namespace detail {

std::string expectation(const Spec& s) {
  switch (s.kind) {
    case Kind::kReal:
      return "a number" + (s.unit.empty() ? std::string() : " in " + s.unit) + " within " + rangeText(s);
    case Kind::kInteger:
      return "an integer within " + rangeText(s);
    case Kind::kSeed:
      return "a non-negative integer (64 bit)";
    case Kind::kBool:
      return "true or false";
    case Kind::kChoice:
      return "one of: " + join(s.choices, ", ");
    case Kind::kText:
    case Kind::kIntList:
    case Kind::kRecordList:
      return s.expected;
  }
  return {};
}

std::string rangeText(const Spec& s) {
  switch (s.kind) {
    case Kind::kChoice:
    case Kind::kBool:
      return join(s.choices, "|");
    case Kind::kSeed:
      return "[0, " + std::to_string(std::numeric_limits<std::uint64_t>::max()) + "]";
    case Kind::kIntList:
      return "list of integers in " + formatRange(s.range, true);
    case Kind::kRecordList:
      return s.range_text;
    case Kind::kText:
      return "text";
    case Kind::kReal:
    case Kind::kInteger:
      break;
  }
  return formatRange(s.range, s.kind == Kind::kInteger) + (s.allow_infinity ? " or .inf" : "");
}

std::string unitSuffix(const Spec& s) { return s.unit.empty() ? "" : " " + s.unit; }

std::string formatRecord(const Spec& s, const Record& record) {
  std::vector<std::string> items;
  for (std::size_t i = 0; i < s.fields.size(); ++i) {
    const Spec& f = s.fields[i];
    const std::size_t slot = recordSlot(s, i);
    if (slot >= record.size() || (!s.forms.empty() && std::isnan(record[slot]))) continue;  // another form's field
    const auto number = [&](double v) {
      return f.kind == Kind::kInteger ? std::to_string(static_cast<long long>(v)) : formatYamlReal(v);
    };
    if (f.components == 1) {
      items.push_back(f.key + ": " + number(record[slot]));
      continue;
    }
    std::vector<std::string> parts;
    for (std::size_t j = 0; j < f.components && slot + j < record.size(); ++j)
      parts.push_back(number(record[slot + j]));
    items.push_back(f.key + ": [" + join(parts, ", ") + "]");
  }
  return "{" + join(items, ", ") + "}";
}

std::string plainValue(const Spec& s, const Value& v) {
  switch (s.kind) {
    case Kind::kReal:
      return formatYamlNumber(std::get<double>(v));
    case Kind::kInteger:
      return std::to_string(static_cast<long long>(std::get<double>(v)));
    case Kind::kSeed:
      return std::to_string(std::get<std::uint64_t>(v));
    case Kind::kBool:
      return std::get<bool>(v) ? "true" : "false";
    case Kind::kChoice:
      return std::get<std::string>(v).empty() ? "<invalid>" : std::get<std::string>(v);
    case Kind::kText:
      return "\"" + std::get<std::string>(v) + "\"";  // kTextChars need no escape
    case Kind::kIntList: {
      std::vector<std::string> items;
      for (const long long i : std::get<std::vector<long long>>(v)) items.push_back(std::to_string(i));
      return "[" + join(items, ", ") + "]";
    }
    case Kind::kRecordList: {
      std::vector<std::string> items;
      for (const Record& r : std::get<std::vector<Record>>(v)) items.push_back(formatRecord(s, r));
      return "[" + join(items, ", ") + "]";
    }
  }
  return {};
}

std::string yamlValue(const Spec& s, const Value& v) {
  return s.kind == Kind::kReal ? formatYamlReal(std::get<double>(v)) : plainValue(s, v);
}

}  // namespace detail

namespace {

using namespace detail;

std::string dumpComment(const Spec& s) {
  switch (s.kind) {
    case Kind::kChoice:
    case Kind::kBool:
      return join(s.choices, " | ");
    case Kind::kIntList:
    case Kind::kRecordList:
      return s.comment;
    case Kind::kText:
      return s.expected;
    case Kind::kReal:
    case Kind::kInteger:
    case Kind::kSeed:
      break;
  }
  return s.unit + (s.allow_infinity ? " (.inf = never)" : "");
}

const char* typeName(const Spec& s) {
  switch (s.kind) {
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
    case Kind::kText:
      return "text";
    case Kind::kIntList:
      return "int list";
    case Kind::kRecordList:
      return s.type_name.c_str();
  }
  return "";
}

std::vector<std::string> sectionsOf(const std::string& key) {
  std::vector<std::string> out;
  for (auto dot = key.find('.'); dot != std::string::npos; dot = key.find('.', dot + 1)) {
    out.push_back(key.substr(0, dot));
  }
  return out;
}

}  // namespace

std::string dump(const Schema& schema, const Values& values) {
  // Comments are aligned anew from each mounted section on, so a mounted configuration reads as it does alone.
  std::string out = "# " + schema.title + ": every parameter, as used\n";
  std::vector<CommentedLine> group;
  std::vector<std::string> open;  // the sections the previous key was in
  for (const Spec& s : schema.specs) {
    const std::vector<std::string> sections = sectionsOf(s.key);
    std::size_t same = 0;
    while (same < open.size() && same < sections.size() && open[same] == sections[same]) ++same;
    for (std::size_t level = same; level < sections.size(); ++level) {
      const std::string indent(2 * level, ' ');
      const std::string name = sections[level].substr(level == 0 ? 0 : sections[level - 1].size() + 1);
      const auto mount = schema.mounts.find(sections[level]);
      if (mount == schema.mounts.end()) {
        group.push_back({indent + name + ":", ""});
        continue;
      }
      out += alignComments(group);
      group.clear();
      out += indent + name + ":  # " + mount->second + "\n";
    }
    open = sections;
    const std::string indent(2 * sections.size(), ' ');
    const std::string leaf = s.key.substr(sections.empty() ? 0 : sections.back().size() + 1);
    const Value& v = values.at(s.key);
    if (s.kind == Kind::kRecordList && !std::get<std::vector<Record>>(v).empty()) {
      // One element per line, so a long list does not push every comment to the right.
      group.push_back({indent + leaf + ":", dumpComment(s)});
      for (const Record& r : std::get<std::vector<Record>>(v))
        group.push_back({indent + "  - " + formatRecord(s, r), ""});
      continue;
    }
    if (const Applies* a = schema.unused(s.key, values)) {
      // Written, so the reader sees it exists, but not read back: giving it would be an error.
      group.push_back({indent + "# " + leaf + ": " + yamlValue(s, v), "not used: " + a->what + " only"});
      continue;
    }
    group.push_back({indent + leaf + ": " + yamlValue(s, v), dumpComment(s)});
  }
  return out + alignComments(group);
}

std::string describe(const Schema& schema, const Values& defaults) {
  std::vector<std::vector<std::string>> rows = {{"key", "type", "unit", "default", "range", "meaning"}};
  for (const Spec& s : schema.specs) {
    rows.push_back({s.key, typeName(s), s.unit.empty() ? "-" : s.unit, plainValue(s, defaults.at(s.key)), rangeText(s),
                    s.meaning});
  }
  for (const Alias& a : schema.aliases) rows.push_back({a.alias, "alias", "-", "-", "-", "the same as " + a.key});
  // Keys used only in some modes, grouped by the case they apply to.
  std::vector<std::pair<std::string, std::vector<std::string>>> cases;  // "what (when: values)" -> keys
  for (const Applies& a : schema.applies) {
    const Spec* when_spec = schema.find(a.when);
    const std::string off = when_spec != nullptr && when_spec->kind == Kind::kText ? " not empty" : " not 0";
    const std::string when = a.values.empty() ? a.when + off : a.when + ": " + join(a.values, ", ");
    const std::string name = a.what + " (" + when + ")";
    auto it = std::find_if(cases.begin(), cases.end(), [&](const auto& c) { return c.first == name; });
    if (it == cases.end()) it = cases.insert(cases.end(), {name, {}});
    it->second.push_back(a.key);
  }
  std::string applies;
  if (!cases.empty()) {
    applies =
        "\nKeys used only in some modes (given otherwise they change nothing, so giving one is an error, unless the\n"
        "file gave it and a --set turned it off):\n";
    for (const auto& c : cases) applies += "  - " + join(c.second, ", ") + ": " + c.first + ".\n";
  }
  return schema.title +
         " parameters. In the YAML file a key a.b is written nested (a map 'a:' holding 'b:'); on the command\n"
         "line use --set a.b=value. Ranges: [ ] includes the bound, ( ) excludes it; '-' = dimensionless.\n\n" +
         formatTable(rows) + applies + (schema.notes.empty() ? "" : "\n" + schema.notes);
}

}  // namespace swa::params

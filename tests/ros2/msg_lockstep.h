#pragma once
// The IDL (SWA's source of message types) against the ROS 2 interface package idl/swa_msgs/msg/*.msg: every struct has
// a .msg of its name with the same fields in the same order and the wire-identical ROS type, and the constants and
// enum values of an IDL file are the constants of the .msg of its main struct (the struct named like the file).
// Mapping: int32/uint32/int64/uint64 as such, double -> float64, boolean -> bool, string -> string, an enum -> uint32
// (IDL enums are 32-bit on the wire), sequence<T> -> T[], sequence<T, N> -> T[<=N], a struct -> its name.
// A parser for exactly the IDL SWA writes (modules, @annotations, structs, enums, consts, sequences, comments), not
// for IDL at large; anything else it meets is a problem it reports. The foreign types (idl/ros: ROS 2 packages) are
// read by the same parser: a qualified type `pkg::msg::Name` becomes `pkg/Name`, and each struct records its package
// (its outermost module), so that test_foreign_definitions.cpp can hold them against the upstream .msg files.

#include <cctype>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace swa::testing::lockstep {

struct Field {
  std::string type;  // ROS spelling after the mapping, e.g. "float64", "Detection[]", "int32[<=64]"
  std::string name;
  bool operator==(const Field& o) const { return type == o.type && name == o.name; }
};

struct Constant {
  std::string type, name, value;
  bool operator<(const Constant& o) const { return name < o.name; }
  bool operator==(const Constant& o) const { return type == o.type && name == o.name && value == o.value; }
};

struct Message {
  std::string package;  // the struct's outermost module (IDL) or the package it was read as (.msg)
  std::vector<Field> fields;
  std::set<Constant> constants;
};

using Messages = std::map<std::string, Message>;  // by message (struct) name

inline std::string readFile(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// Problems one per line, for a failure message.
inline std::string lines(const std::vector<std::string>& problems) {
  std::string s;
  for (const std::string& p : problems) s += "  " + p + "\n";
  return s;
}

namespace detail {

inline std::vector<std::string> tokens(const std::string& text, std::vector<std::string>& problems) {
  std::vector<std::string> out;
  std::size_t k = 0;
  while (k < text.size()) {
    const char c = text[k];
    if (std::isspace(static_cast<unsigned char>(c))) {
      ++k;
    } else if (text.compare(k, 2, "//") == 0 || c == '#') {  // comments and preprocessor lines
      k = text.find('\n', k);
      if (k == std::string::npos) break;
    } else if (text.compare(k, 2, "/*") == 0) {
      k = text.find("*/", k);
      if (k == std::string::npos) break;
      k += 2;
    } else if (c == '@') {  // an annotation (@final, @extensibility(FINAL)): not a field or type
      ++k;
      while (k < text.size() && (std::isalnum(static_cast<unsigned char>(text[k])) || text[k] == '_')) ++k;
      if (k < text.size() && text[k] == '(') k = text.find(')', k) + 1;
    } else if (std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-') {
      std::size_t e = k + 1;
      // a qualified name (a::b::C) and a fixed array's declarator (name[36]) are one token each
      const auto word = [&](std::size_t i) {
        return std::isalnum(static_cast<unsigned char>(text[i])) ||
               std::string("_.[]").find(text[i]) != std::string::npos;
      };
      while (e < text.size() && (word(e) || text.compare(e, 2, "::") == 0)) e += text.compare(e, 2, "::") == 0 ? 2 : 1;
      out.push_back(text.substr(k, e - k));
      k = e;
    } else if (std::string("{};<>,=").find(c) != std::string::npos) {
      out.emplace_back(1, c);
      ++k;
    } else {
      problems.push_back(std::string("unexpected character '") + c + "'");
      ++k;
    }
  }
  return out;
}

inline std::string rosPrimitive(const std::string& idl) {
  static const std::map<std::string, std::string> kMap = {
      {"int32", "int32"},    {"uint32", "uint32"}, {"int64", "int64"},  {"uint64", "uint64"},
      {"double", "float64"}, {"float", "float32"}, {"boolean", "bool"}, {"string", "string"},
      {"int8", "int8"},      {"uint8", "uint8"},   {"int16", "int16"},  {"uint16", "uint16"}};
  const auto it = kMap.find(idl);
  return it == kMap.end() ? "" : it->second;
}

// "geometry_msgs::msg::Pose" -> "geometry_msgs/Pose" (the ROS spelling of another package's type); a bare name stays.
inline std::string rosQualified(const std::string& idl) {
  const std::size_t first = idl.find("::");
  if (first == std::string::npos) return idl;
  return idl.substr(0, first) + "/" + idl.substr(idl.rfind("::") + 2);
}

}  // namespace detail

// Parses one IDL file named `file_stem` (e.g. "Detections") into `out`; returns the problems found.
inline std::vector<std::string> parseIdl(const std::string& file_stem, const std::string& text, Messages& out) {
  std::vector<std::string> problems;
  const std::vector<std::string> t = detail::tokens(text, problems);
  std::set<std::string> enums;
  std::set<Constant> file_constants;
  std::vector<std::string> structs;
  std::size_t k = 0;
  const auto at = [&](std::size_t i) { return i < t.size() ? t[i] : std::string(); };
  const auto mapType = [&](const std::string& idl) {
    if (const std::string p = detail::rosPrimitive(idl); !p.empty()) return p;
    if (enums.count(idl) != 0) return std::string("uint32");
    return detail::rosQualified(idl);  // a struct: bare of the same package, qualified of another
  };
  std::vector<std::string> modules;  // open modules, outermost first (a struct's or enum's "}" is read with it)

  while (k < t.size()) {
    const std::string& w = t[k];
    if (w == "module") {
      modules.push_back(at(k + 1));
      k += 3;  // module NAME {
    } else if (w == "}") {
      if (!modules.empty()) modules.pop_back();
      ++k;
    } else if (w == ";") {
      ++k;
    } else if (w == "const") {  // const TYPE NAME = VALUE ;
      file_constants.insert({mapType(at(k + 1)), at(k + 2), at(k + 4)});
      k += 6;
    } else if (w == "enum") {  // enum NAME { A , B , ... } ;
      enums.insert(at(k + 1));
      k += 3;
      int value = 0;
      while (k < t.size() && t[k] != "}") {
        if (t[k] != ",") file_constants.insert({"uint32", t[k], std::to_string(value++)});
        ++k;
      }
      ++k;                       // its "}"
    } else if (w == "struct") {  // struct NAME { fields } ;
      const std::string name = at(k + 1);
      structs.push_back(name);
      Message& m = out[name];
      m.package = modules.empty() ? std::string() : modules.front();
      k += 3;
      while (k < t.size() && t[k] != "}") {
        if (t[k] == "sequence") {  // sequence < T [, N] > name ;
          const std::string element = mapType(at(k + 2));
          std::string bound;
          k += 3;
          if (at(k) == ",") {
            bound = "<=" + at(k + 1);
            k += 2;
          }
          m.fields.push_back({element + "[" + bound + "]", at(k + 1)});
          k += 3;
        } else {  // TYPE NAME ; or TYPE NAME[N] ; (a fixed array: ROS spells it TYPE[N] NAME)
          const std::string declarator = at(k + 1);
          const std::size_t bracket = declarator.find('[');
          m.fields.push_back({mapType(t[k]) + (bracket == std::string::npos ? "" : declarator.substr(bracket)),
                              declarator.substr(0, bracket)});
          if (at(k + 2) != ";") problems.push_back(file_stem + ": cannot read the field after " + t[k]);
          k += 3;
        }
      }
      ++k;  // its "}"
    } else {
      problems.push_back(file_stem + ".idl: unexpected '" + w + "'");
      ++k;
    }
  }
  if (!file_constants.empty()) {
    if (out.count(file_stem) == 0) {
      problems.push_back(file_stem + ".idl declares constants but no struct " + file_stem + " to carry them");
    } else {
      out[file_stem].constants.insert(file_constants.begin(), file_constants.end());
    }
  }
  if (structs.empty() && !file_constants.empty()) problems.push_back(file_stem + ".idl has no struct");
  return problems;
}

// Parses one .msg file into `out`; returns the problems found. Types are kept as written (a bare name is of the
// message's own package).
inline std::vector<std::string> parseMsg(const std::string& name, const std::string& text, Message& out) {
  std::vector<std::string> problems;
  std::istringstream lines(text);
  std::string line;
  while (std::getline(lines, line)) {
    if (const std::size_t hash = line.find('#'); hash != std::string::npos) line.erase(hash);
    std::istringstream words(line);
    std::string type, rest;
    if (!(words >> type)) continue;
    std::getline(words, rest);
    rest.erase(0, rest.find_first_not_of(" \t"));
    rest.erase(rest.find_last_not_of(" \t") + 1);
    if (const std::size_t eq = rest.find('='); eq != std::string::npos) {
      std::string cname = rest.substr(0, eq), value = rest.substr(eq + 1);
      cname.erase(cname.find_last_not_of(" \t") + 1);
      value.erase(0, value.find_first_not_of(" \t"));
      out.constants.insert({type, cname, value});
    } else if (rest.empty()) {
      problems.push_back(name + ".msg: cannot read '" + line + "'");
    } else {  // NAME, or NAME DEFAULT (ROS 2: a default value, which is not on the wire)
      out.fields.push_back({type, rest.substr(0, rest.find_first_of(" \t"))});
    }
  }
  return problems;
}

// Every difference between the messages of the IDL and those of the .msg files, one line each; empty when in
// lock-step.
inline std::vector<std::string> compare(const Messages& idl, const Messages& msg) {
  std::vector<std::string> problems;
  for (const auto& [name, m] : idl) {
    const auto it = msg.find(name);
    if (it == msg.end()) {
      problems.push_back("IDL struct " + name + " has no " + name + ".msg");
      continue;
    }
    const Message& r = it->second;
    const std::size_t n = std::max(m.fields.size(), r.fields.size());
    for (std::size_t k = 0; k < n; ++k) {
      const std::string want = k < m.fields.size() ? m.fields[k].type + " " + m.fields[k].name : "(nothing)";
      const std::string have = k < r.fields.size() ? r.fields[k].type + " " + r.fields[k].name : "(nothing)";
      if (want != have) {
        problems.push_back(name + ": field " + std::to_string(k + 1) + " is '" + have + "' in " + name +
                           ".msg, the IDL says '" + want + "'");
      }
    }
    for (const Constant& c : m.constants) {
      const auto found = r.constants.find(c);
      if (found == r.constants.end() || !(*found == c)) {
        problems.push_back(name + ".msg lacks the constant '" + c.type + " " + c.name + "=" + c.value + "'");
      }
    }
    for (const Constant& c : r.constants) {
      if (m.constants.count(c) == 0) problems.push_back(name + ".msg has a constant the IDL lacks: " + c.name);
    }
  }
  for (const auto& [name, r] : msg) {
    if (idl.count(name) == 0) problems.push_back(name + ".msg has no IDL struct " + name);
  }
  return problems;
}

}  // namespace swa::testing::lockstep

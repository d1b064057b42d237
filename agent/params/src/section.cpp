#include "swa/params/section.h"

#include <yaml-cpp/yaml.h>

#include <set>

#include "swa/params/error.h"
#include "swa/params/file.h"
#include "yaml_error.h"
#include "yaml_node.h"

namespace swa::params {
namespace {

using detail::locationOf;
using detail::nodeKindName;

constexpr std::size_t kMaxLeaves = 2000;  // as many keys as a whole parameter file may have (read.cpp)

class SectionReader {
 public:
  explicit SectionReader(std::string name) : name_(std::move(name)) {}

  void read(const std::string& text) {
    std::vector<YAML::Node> documents;
    try {
      documents = YAML::LoadAll(text);
    } catch (const YAML::Exception& e) {
      unreadable_ = detail::yamlErrorText(e, text);
      return;
    }
    // Several documents or a top level that is not a map: the file's own loader says so.
    if (documents.size() != 1 || !documents.front().IsMap()) return;
    for (const auto& item : documents.front()) {
      if (!item.first.IsScalar() || item.first.Scalar() != name_) continue;
      if (section_.present) {
        section_.problems.push_back("'" + name_ + "' given twice" + locationOf(item.first));
        continue;
      }
      section_.present = true;
      if (item.second.IsMap()) {
        walk(item.second, "");
      } else if (!item.second.IsNull()) {
        section_.problems.push_back("'" + name_ + "' must be a map, got " + nodeKindName(item.second) +
                                    locationOf(item.second));
      }
    }
  }

  Section take(const std::string& source) {
    if (!unreadable_.empty()) throw ConfigError(source, {unreadable_});
    return std::move(section_);
  }

 private:
  void walk(const YAML::Node& map, const std::string& prefix) {
    for (const auto& item : map) {
      const std::string at = prefix.empty() ? name_ : name_ + "." + prefix;
      if (!item.first.IsScalar()) {
        section_.problems.push_back("a key under '" + at + "' is " + nodeKindName(item.first) + ", not a name" +
                                    locationOf(item.first));
        continue;
      }
      const std::string key = prefix.empty() ? item.first.Scalar() : prefix + "." + item.first.Scalar();
      const YAML::Node& value = item.second;
      if (!seen_.insert(key).second) {
        section_.problems.push_back(name_ + "." + key + " given twice" + locationOf(item.first));
        continue;
      }
      if (section_.leaves.size() >= kMaxLeaves) {
        section_.problems.push_back("'" + name_ + "' has more than " + std::to_string(kMaxLeaves) + " entries");
        return;
      }
      if (value.IsMap()) {
        walk(value, key);
      } else if (value.IsScalar()) {
        section_.leaves.push_back({key, {value.Scalar()}, false, locationOf(value)});
      } else if (value.IsSequence()) {
        SectionLeaf leaf{key, {}, true, locationOf(value)};
        bool plain = true;
        for (const YAML::Node& element : value) {
          if (element.IsScalar()) {
            leaf.values.push_back(element.Scalar());
          } else if (plain) {
            plain = false;
            section_.problems.push_back("'" + name_ + "." + key + "' must list plain values, got " +
                                        nodeKindName(element) + locationOf(element));
          }
        }
        if (plain) section_.leaves.push_back(std::move(leaf));
      } else {
        section_.problems.push_back("'" + name_ + "." + key + "' has no value" + locationOf(item.first));
      }
    }
  }

  const std::string name_;
  Section section_;
  std::set<std::string> seen_;  // dotted keys below the section, to catch one written twice
  std::string unreadable_;
};

}  // namespace

Section parseSection(const std::string& text, const std::string& source, const std::string& name) {
  SectionReader reader(name);
  reader.read(text);
  return reader.take(source);
}

Section readSection(const std::string& path, const std::string& kind, const std::string& name) {
  std::string problem;
  const std::optional<std::string> text = readTextFile(path, kind, problem);
  if (!text) throw ConfigError(path, {problem});
  return parseSection(*text, path, name);
}

}  // namespace swa::params

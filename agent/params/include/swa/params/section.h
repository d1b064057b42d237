#pragma once
// A section of a parameter file that the file's schema leaves to another reader (Schema::foreign_sections): the
// scenario's `study:` holds swa_batch's sweep, so a study is one file under version control, and every other
// program reading the scenario skips it. The section comes back as text; its reader gives it meaning.

#include <string>
#include <vector>

namespace swa::params {

struct SectionLeaf {
  std::string key;                  // dotted, below the section: "sweep.uav_count"
  std::vector<std::string> values;  // a scalar: one value; a sequence of scalars: each, in order
  bool sequence = false;
  std::string where;  // " (line L, column C)"
};

struct Section {
  bool present = false;             // the file has the section (an empty one counts)
  std::vector<SectionLeaf> leaves;  // in file order (nested maps flattened into dotted keys)
  // What is wrong with the section's shape (anything but maps, scalars and sequences of scalars): its reader adds
  // its own problems and reports them all together.
  std::vector<std::string> problems;
};

// Section `name` of the parameter file at `path` (`kind` names the file in messages: "scenario"). Throws ConfigError
// (source = path) if the file cannot be read or is not YAML. The rest of the file is not judged here: its own loader
// does that.
Section readSection(const std::string& path, const std::string& kind, const std::string& name);
// As readSection, from YAML text; `source` names it in messages.
Section parseSection(const std::string& text, const std::string& source, const std::string& name);

}  // namespace swa::params

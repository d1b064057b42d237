#pragma once
// The parameter engine: reading a parameter file and `--set key=value` overrides against a Schema, validating
// values built in code, writing the effective parameters as YAML, and describing the parameters for --help.
//
// A file mirrors the dotted keys as nested maps; keys left out keep the values given as `values`. Every problem
// (file, YAML syntax, unknown keys with a did-you-mean, wrong types, bounds with units, non-finite values, invalid
// choices, alias conflicts, malformed or invalid overrides, rules between parameters) is reported together in one
// ConfigError. File problems carry "(line L, column C)", override problems "(from --set key=value)". A later
// override of a key wins; rules are judged on the final values (and not at all over a file that could not be read).

#include <string>
#include <vector>

#include "swa/params/error.h"
#include "swa/params/schema.h"

namespace swa::params {

// The parameter file at `path` (a regular text file of at most 1 MiB and 2000 keys: file.h) and the overrides on
// top of `values`. Throws ConfigError (source = path).
Values loadFile(const Schema& schema, Values values, const std::string& path,
                const std::vector<std::string>& overrides);

// As loadFile, from YAML text; `source` names it in messages. An empty text changes nothing.
Values parseText(const Schema& schema, Values values, const std::string& text, const std::string& source,
                 const std::vector<std::string>& overrides);

// As parseText, for a text a program wrote (a dump, perhaps of an older version that wrote every key): keys that
// its own choices turn off are not refused from it; the overrides are judged as ever.
Values parseDump(const Schema& schema, Values values, const std::string& text, const std::string& source,
                 const std::vector<std::string>& overrides);

// Every value within its bounds and every rule kept, else ConfigError (source = `source`) listing each violation.
void validate(const Schema& schema, const Values& values, const std::string& source);

// Every parameter as commented YAML (units, choices) that reads back to exactly these values.
std::string dump(const Schema& schema, const Values& values);

// A table of every parameter (key, type, unit, default, range, meaning), its aliases, and the schema's notes.
std::string describe(const Schema& schema, const Values& defaults);

}  // namespace swa::params

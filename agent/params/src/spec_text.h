#pragma once
// Internal to the engine: how a parameter and its value are worded, shared by reading (read.cpp) and writing
// (layout.cpp) so a message, the dump and the description always agree.

#include <string>

#include "swa/params/schema.h"

namespace swa::params::detail {

// What a valid value is: "a number in m within (0, 1000]", "one of: swa, standalone, anchored", ...
std::string expectation(const Spec& spec);
// The range column and the bounds in messages: "(0, 1000]", "fixed_radius|algebraic", ...
std::string rangeText(const Spec& spec);
std::string unitSuffix(const Spec& spec);
// A value in messages and the description ("10", ".inf", "[0, 3]"); in the dump reals keep a '.'.
std::string plainValue(const Spec& spec, const Value& value);
std::string yamlValue(const Spec& spec, const Value& value);
std::string formatRecord(const Spec& spec, const Record& record);

}  // namespace swa::params::detail

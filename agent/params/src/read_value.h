#pragma once
// Internal to the engine: one value as YAML gave it, checked against its Spec into a Value. read.cpp turns a file's
// or a --set's entries into values with it; every message names the parameter as the user wrote it.

#include <yaml-cpp/yaml.h>

#include <functional>
#include <optional>
#include <string>

#include "swa/params/schema.h"

namespace swa::params::detail {

// Told each problem, and the node it is about: an element of a list has a line of its own in a file; nullptr means
// the value itself.
using ValueFail = std::function<void(std::string message, const YAML::Node* at)>;

// The value of `node` for `spec` (written as `name`), or nullopt once `fail` has been told every problem.
std::optional<Value> readValue(const Spec& spec, const YAML::Node& node, const std::string& name,
                               const ValueFail& fail);

// Why `v` (shown as `shown`) is not a valid number for `spec`, if it is not.
std::optional<std::string> numberProblem(const Spec& spec, double v, const std::string& name, const std::string& shown);

// Whether `text` is a valid value of a Kind::kText parameter.
bool isText(const std::string& text);

}  // namespace swa::params::detail

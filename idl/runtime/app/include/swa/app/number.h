#pragma once
// Numbers read from text given by a person or a file (command lines, environment, CSV): the whole text or nothing,
// so "3x", " 3", "nan" and overflow are rejected instead of half-read.

#include <optional>
#include <string>

namespace swa::app {

// The integer / finite real spelled by all of `text`, if it lies in [min, max]; nullopt otherwise.
std::optional<long long> parseInteger(const std::string& text, long long min, long long max);
std::optional<double> parseReal(const std::string& text, double min, double max);

// `value` as a person writes it in a message or a help text: 0.001, 2, 1000000 (no exponent, no trailing zeros).
std::string formatNumber(double value);

}  // namespace swa::app

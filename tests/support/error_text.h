#pragma once
// Shared by the tests of command lines and settings: what a parse refused, as the user reads it.

#include <stdexcept>
#include <string>

namespace swa::testing {

// The message of the std::invalid_argument `parse()` throws, "" when it throws none.
template <class Parse>
std::string invalidArgumentText(Parse&& parse) {
  try {
    parse();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

}  // namespace swa::testing

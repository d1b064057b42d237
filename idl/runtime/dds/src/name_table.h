#pragma once
// An enum's names in one list, read both ways (SWA_TRANSPORT, SWA_NAMING): private to swa_dds.

#include <cstddef>
#include <optional>
#include <string>
#include <utility>

namespace swa::dds::detail {

template <class Enum, std::size_t N>
const char* nameIn(const std::pair<Enum, const char*> (&names)[N], Enum value) {
  for (const auto& [v, name] : names) {
    if (v == value) return name;
  }
  return "?";
}

template <class Enum, std::size_t N>
std::optional<Enum> valueIn(const std::pair<Enum, const char*> (&names)[N], const std::string& name) {
  for (const auto& [v, known] : names) {
    if (name == known) return v;
  }
  return std::nullopt;
}

}  // namespace swa::dds::detail

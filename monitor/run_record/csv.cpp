#include "swa/run_record/csv.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>

namespace swa::record {

std::optional<std::vector<std::string>> splitCsvLine(std::string_view line) {
  std::vector<std::string> fields;
  std::string field;
  std::size_t k = 0;
  while (true) {
    field.clear();
    if (k < line.size() && line[k] == '"') {
      ++k;
      while (true) {
        if (k >= line.size()) return std::nullopt;  // unterminated quote
        if (line[k] == '"') {
          if (k + 1 < line.size() && line[k + 1] == '"') {
            field += '"';
            k += 2;
            continue;
          }
          ++k;
          break;
        }
        field += line[k++];
      }
      if (k < line.size() && line[k] != ',') return std::nullopt;  // text after the closing quote
    } else {
      while (k < line.size() && line[k] != ',') field += line[k++];
    }
    fields.push_back(field);
    if (k >= line.size()) return fields;
    ++k;  // the comma
  }
}

std::string csvField(std::string_view text) {
  std::string flat(text);
  for (char& c : flat) {
    if (c == '\n' || c == '\r') c = ' ';
  }
  const bool quote =
      flat.find_first_of(",\"") != std::string::npos || (!flat.empty() && (flat.front() == ' ' || flat.back() == ' '));
  if (!quote) return flat;
  std::string out = "\"";
  for (const char c : flat) {
    if (c == '"') out += '"';
    out += c;
  }
  out += '"';
  return out;
}

std::string_view chompCr(std::string_view line) {
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  return line;
}

std::optional<double> csvNumber(const std::string& text) {
  if (text.empty() || std::isspace(static_cast<unsigned char>(text.front()))) return std::nullopt;
  errno = 0;
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (end != text.c_str() + text.size() || (errno == ERANGE && std::isinf(v))) return std::nullopt;
  return v;
}

}  // namespace swa::record

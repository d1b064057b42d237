#include "swa/params/file.h"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <system_error>

namespace swa::params {

std::optional<std::string> readTextFile(const std::string& path, const std::string& kind, std::string& problem) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (!fs::exists(status)) {
    problem = kind + " file does not exist";
    return std::nullopt;
  }
  if (fs::is_directory(status)) {
    problem = "is a directory, not a " + kind + " file";
    return std::nullopt;
  }
  if (!fs::is_regular_file(status)) {
    problem = "is a device, pipe or socket, not a " + kind + " file";
    return std::nullopt;
  }
  const std::uintmax_t size = fs::file_size(path, ec);
  if (!ec && size > kMaxFileBytes) {
    problem = "is " + std::to_string(size) + " bytes; a " + kind + " file may have at most " +
              std::to_string(kMaxFileBytes) + " (1 MiB)";
    return std::nullopt;
  }
  std::ifstream file(path, std::ios::binary);
  if (!file.is_open()) {
    problem = kind + " file cannot be opened: " + std::strerror(errno);
    return std::nullopt;
  }
  // Read at most one byte more than the limit: the size may have changed since it was checked.
  std::string text(kMaxFileBytes + 1, '\0');
  file.read(text.data(), static_cast<std::streamsize>(text.size()));
  if (file.bad()) {
    problem = kind + " file cannot be read";
    return std::nullopt;
  }
  text.resize(static_cast<std::size_t>(file.gcount()));
  if (text.size() > kMaxFileBytes) {
    problem = "is larger than " + std::to_string(kMaxFileBytes) + " bytes (1 MiB), the limit of a " + kind + " file";
    return std::nullopt;
  }
  if (text.find('\0') != std::string::npos) {
    problem = "is not a text file (it contains NUL bytes)";
    return std::nullopt;
  }
  return text;
}

std::vector<std::string> summariseProblems(const std::vector<std::string>& problems) {
  std::vector<std::string> order;
  std::map<std::string, std::size_t> count;
  for (std::string p : problems) {
    if (p.size() > kMaxProblemChars) p = p.substr(0, kMaxProblemChars - 3) + "...";
    if (count[p]++ == 0) order.push_back(p);
  }
  std::vector<std::string> out;
  for (const std::string& p : order) {
    if (out.size() == kMaxProblems) break;
    const std::size_t n = count[p];
    out.push_back(n > 1 ? p + " (" + std::to_string(n) + " times)" : p);
  }
  if (order.size() > kMaxProblems) {
    out.push_back("... and " + std::to_string(order.size() - kMaxProblems) + " more distinct problems");
  }
  return out;
}

}  // namespace swa::params

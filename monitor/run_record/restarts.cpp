#include "swa/run_record/restarts.h"

#include <fstream>
#include <limits>
#include <optional>

#include "swa/app/number.h"
#include "swa/run_record/csv.h"

namespace swa::record {
namespace {

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t");
  if (b == std::string::npos) return "";
  return s.substr(b, s.find_last_not_of(" \t") - b + 1);
}

// nullopt and `why` set when the row is malformed.
std::optional<AgentRestart> parseRow(std::string_view line, std::string& why) {
  const auto fields = splitCsvLine(line);
  if (!fields) {
    why = "unbalanced quotes";
    return std::nullopt;
  }
  if (fields->size() != 5) {
    why = std::to_string(fields->size()) + " fields, expected 5";
    return std::nullopt;
  }
  std::vector<std::string> f;
  for (const std::string& x : *fields) f.push_back(trim(x));
  AgentRestart r;
  const auto wall = app::parseReal(f[0], 0.0, 1e12);
  const std::string prefix = kBridgePrefix;
  r.bridge = f[1].rfind(prefix, 0) == 0;
  const auto uav = f[1] == "monitor" ? std::optional<long long>(AgentRestart::kMonitor)
                                     : app::parseInteger(r.bridge ? f[1].substr(prefix.size()) : f[1], 0, 1'000'000);
  const auto count = app::parseInteger(f[3], 0, std::numeric_limits<long long>::max());
  const auto backoff = app::parseReal(f[4], 0.0, 1e12);
  // The first problem of the row is the one reported.
  why = !wall          ? "wall_s '" + f[0] + "' is not a time >= 0"
        : !uav         ? "uav '" + f[1] + "' is not a UAV index, bridge_<index> or monitor"
        : f[2].empty() ? std::string("exit_status is empty")
        : !count       ? "restart_count '" + f[3] + "' is not a count >= 0"
        : !backoff     ? "backoff_s '" + f[4] + "' is not a time >= 0"
                       : std::string();
  if (!why.empty()) return std::nullopt;
  r.wall_s = *wall;
  r.uav = static_cast<int>(*uav);
  r.exit_status = f[2];
  r.restart_count = static_cast<std::int64_t>(*count);
  r.backoff_s = *backoff;
  return r;
}

}  // namespace

std::string restartSubject(const AgentRestart& r) {
  if (r.uav == AgentRestart::kMonitor) return "monitor";
  return (r.bridge ? std::string(kBridgePrefix) : std::string()) + std::to_string(r.uav);
}

RestartLog parseRestartLog(std::istream& in) {
  RestartLog log;
  log.found = true;
  std::string raw;
  for (int line_no = 1; std::getline(in, raw); ++line_no) {
    const std::string line = trim(std::string(chompCr(raw)));
    if (line.empty() || line == restartLogHeader()) continue;
    std::string why;
    if (auto row = parseRow(line, why)) {
      log.restarts.push_back(std::move(*row));
      continue;
    }
    ++log.malformed_rows;
    if (log.problems.size() < RestartLog::kMaxProblems) {
      log.problems.push_back("line " + std::to_string(line_no) + ": " + why);
    }
  }
  return log;
}

RestartLog readRestartLog(const std::string& path) {
  std::ifstream in(path);
  if (!in) return RestartLog{};
  return parseRestartLog(in);
}

}  // namespace swa::record

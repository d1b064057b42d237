#pragma once
// The CSV dialect of a run directory's files (timeseries.csv, trajectories.csv, events.csv, the launcher's restart
// log): one record per line, comma separated, RFC 4180 quoting ("a, b" and "" for a quote inside quotes), CRLF
// tolerated on reading.

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace swa::record {

// The fields of one line (without its line break); nullopt when a quoted field is not closed or text follows a
// closing quote.
std::optional<std::vector<std::string>> splitCsvLine(std::string_view line);

// A field for writing: line breaks become spaces (a record stays on one line), then the text is quoted when it
// contains a comma, a quote or leading / trailing spaces.
std::string csvField(std::string_view text);

// Drops one trailing '\r' (a file written on Windows, or by a tool that writes CRLF).
std::string_view chompCr(std::string_view line);

// A whole field as a number ("nan" and "inf" included, as monitor::formatNumber writes them).
std::optional<double> csvNumber(const std::string& text);

}  // namespace swa::record

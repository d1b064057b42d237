#pragma once
// Internal to the report: how its numbers and file names are written, the same in the plots (report_plots.cpp) and
// the page (report_html.cpp).

#include <cstddef>
#include <string>

#include "swa/monitor/svg_plot.h"

namespace swa::monitor {

inline std::string percentText(double fraction) { return formatFixed(100.0 * fraction, 1) + " %"; }

inline std::string metresText(double value) { return formatFixed(value, 3) + " m"; }

// A run's label as a file or anchor name: letters, digits, '_' and '-' kept, anything else '_'; "run<N>" if empty.
inline std::string reportFileStem(const std::string& label, std::size_t index) {
  std::string stem;
  for (const char c : label) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == '-';
    stem += ok ? c : '_';
  }
  return stem.empty() ? "run" + std::to_string(index + 1) : stem;
}

}  // namespace swa::monitor

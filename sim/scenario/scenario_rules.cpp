// The rules between scenario parameters and their --help text (scenario_rules.h), apart from the table of the
// parameters themselves (scenario_io.cpp).
#include "scenario_rules.h"

#include <cmath>
#include <set>
#include <sstream>
#include <string>

#include "swa/params/text.h"

namespace swa::sim {

namespace {

using params::formatYamlNumber;
using params::Values;

std::string uavIndices(const Values& v) {
  const int n = static_cast<int>(params::number(v, "uav_count"));
  return "the UAV indices are 0.." + std::to_string(n - 1) + " (uav_count = " + std::to_string(n) + ")";
}

}  // namespace

std::vector<params::Check> scenarioChecks() {
  std::vector<params::Check> checks;
  for (const std::string key : {"imu.rate_hz", "mps.rate_hz", "gnss.rate_hz"}) {
    checks.push_back({{key, "dynamics.rate_hz"}, [key](const Values& v, std::vector<std::string>& problems) {
                        const double rate = params::number(v, key);
                        const double sim = params::number(v, "dynamics.rate_hz");
                        const double ratio = sim / rate;
                        const double steps = std::round(ratio);
                        if (steps >= 1.0 && std::fabs(ratio - steps) <= 1e-9 * steps) return;
                        std::ostringstream ratio_text;
                        ratio_text.precision(4);
                        ratio_text << ratio;
                        problems.push_back(key + " = " + formatYamlNumber(rate) +
                                           " Hz must divide dynamics.rate_hz = " + formatYamlNumber(sim) +
                                           " Hz exactly: the sensor samples every n-th simulation step, and " +
                                           formatYamlNumber(sim) + " / " + formatYamlNumber(rate) + " = " +
                                           ratio_text.str() + " is not a whole number >= 1");
                      }});
  }
  checks.push_back({{"gnss.dropout_start_s", "gnss.dropout_end_s"}, [](const Values& v, auto& problems) {
                      const double start = params::number(v, "gnss.dropout_start_s");
                      const double end = params::number(v, "gnss.dropout_end_s");
                      if (end > start) return;
                      problems.push_back("gnss.dropout_end_s = " + formatYamlNumber(end) +
                                         " s must be > gnss.dropout_start_s = " + formatYamlNumber(start) +
                                         " s: the outage would be empty (to run without a dropout, set "
                                         "gnss.dropout_start_s >= duration_s)");
                    }});
  checks.push_back({{"gnss.keep_uavs", "uav_count"}, [](const Values& v, auto& problems) {
                      std::set<long long> listed;
                      for (const long long id : params::intList(v, "gnss.keep_uavs")) {
                        if (static_cast<double>(id) >= params::number(v, "uav_count")) {
                          problems.push_back("gnss.keep_uavs lists UAV " + std::to_string(id) + ", but " +
                                             uavIndices(v));
                        } else if (!listed.insert(id).second) {
                          problems.push_back("gnss.keep_uavs lists UAV " + std::to_string(id) + " more than once");
                        }
                      }
                    }});
  checks.push_back({{"gnss.windows", "uav_count"}, [](const Values& v, auto& problems) {
                      const auto& windows = params::records(v, "gnss.windows");
                      for (std::size_t i = 0; i < windows.size(); ++i) {
                        if (windows[i][0] < params::number(v, "uav_count")) continue;
                        problems.push_back("gnss.windows[" + std::to_string(i) +
                                           "].uav = " + std::to_string(static_cast<long long>(windows[i][0])) +
                                           " is not a UAV of the swarm: " + uavIndices(v));
                      }
                    }});
  checks.push_back({{"formation.spacing_m", "mps.range_m"}, [](const Values& v, auto& problems) {
                      const double spacing = params::number(v, "formation.spacing_m");
                      const double range = params::number(v, "mps.range_m");
                      if (spacing < range) return;
                      problems.push_back("formation.spacing_m = " + formatYamlNumber(spacing) +
                                         " m must be < mps.range_m = " + formatYamlNumber(range) +
                                         " m: otherwise no UAV detects its neighbours");
                    }});
  checks.push_back(
      {{"vehicle.px4_origin_shift_at_s", "vehicle.px4_origin_shift_east_m", "vehicle.px4_origin_shift_north_m"},
       [](const Values& v, auto& problems) {
         const bool moved = params::number(v, "vehicle.px4_origin_shift_east_m") != 0.0 ||
                            params::number(v, "vehicle.px4_origin_shift_north_m") != 0.0;
         if (!moved || std::isfinite(params::number(v, "vehicle.px4_origin_shift_at_s"))) return;
         problems.push_back(
             "vehicle.px4_origin_shift_east_m / _north_m move the PX4 stand-ins' local "
             "origin, but vehicle.px4_origin_shift_at_s is .inf (never): give the time");
       }});
  return checks;
}

const char* scenarioRuleNotes() {
  return "Rules between parameters:\n"
         "  - imu.rate_hz, mps.rate_hz and gnss.rate_hz must each divide dynamics.rate_hz exactly.\n"
         "  - gnss.dropout_end_s > gnss.dropout_start_s; gnss.dropout_end_s may be .inf (never restored).\n"
         "  - gnss.keep_uavs: distinct UAV indices in [0, uav_count).\n"
         "  - gnss.windows: extra outages of single UAVs, e.g. [{uav: 3, start_s: 20, end_s: 40}, {uav: 5, start_s: "
         "0}]\n"
         "    (--set gnss.windows='[...]' replaces the whole list). uav in [0, uav_count), 0 <= start_s < end_s;\n"
         "    end_s may be .inf or left out (never restored). A UAV has no GNSS inside the common window (unless it\n"
         "    is in keep_uavs) or inside any of its own windows; windows may overlap.\n"
         "  - formation.spacing_m < mps.range_m.\n"
         "  - vehicle.px4_origin_shift_east_m and _north_m (a shift of the PX4 stand-ins' local origin) need a finite\n"
         "    vehicle.px4_origin_shift_at_s; a shift by 0 m still re-sets the origin (a new ref_timestamp).\n"
         "  - agent.*: the agent configuration (swa_agent --parameters); agent.formation.radius_m defaults to\n"
         "    formation.spacing_m unless given; agent.k and agent.circle_fit are aliases (a file gives one spelling).\n"
         "  - study: a section for swa_batch's studies (seeds and the sweep, see swa_batch --help); every other "
         "program\n"
         "    ignores it.\n";
}

}  // namespace swa::sim

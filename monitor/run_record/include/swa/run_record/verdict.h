#pragma once
// The run's verdict and the process exit status that carries it (monitor_options.h ExitCode).
//   PASS        the scenario completed, final d_NB within r (1 ± tolerance), no collision, one group at the end
//   FAIL        completed, but at least one of those criteria failed
//   INCOMPLETE  the scenario did not complete, no truth was seen at all, or the monitor missed part of the run (it
//               started late or lost the truth for more than a second): the numbers describe a partial run
// INCOMPLETE wins over FAIL; its reasons still list the criteria that failed on the partial run, for the record.

#include <optional>
#include <string>
#include <vector>

#include "swa/monitor/accumulator.h"
#include "swa/monitor/report_html.h"

namespace swa::record {

// A stretch of sim time the monitor did not see (monitor/live_join/truth_coverage.h).
struct MissedSpan {
  double from_s;
  double to_s;
};

enum class Outcome { kPass, kFail, kIncomplete };

struct Verdict {
  Outcome outcome = Outcome::kIncomplete;
  std::vector<std::string> reasons;  // empty for PASS
};

// A vehicle its stand-in autopilot took out of SWA's control and never gave back (EVENT_CONTROL_LOST, no
// EVENT_CONTROL_REGAINED after it): since when, and the stand-in's words.
struct ControlLoss {
  int uav = 0;
  double t_s = 0.0;
  std::string text;
};

struct VerdictInput {
  bool completed = false;  // EVENT_SCENARIO_END "completed" received
  std::string end_reason;  // why the run ended, when not completed
  bool saw_truth = false;  // at least one step was scored
  monitor::Summary summary;
  monitor::MetricsConfig scoring;  // r and its PASS band (radius_tolerance)
  // Parts of the run the monitor did not see: the verdict is INCOMPLETE if there are any.
  std::vector<MissedSpan> missed;
  // UAVs whose agent the last truth calls dead (declared dead, never rejoined): their UAVs ended on the failsafe, so
  // the swarm did not end whole, however well the others held the formation.
  std::vector<int> failsafe_at_end;
  // Vehicles out of SWA's control at the end (a PX4 or ArduPilot failsafe): the swarm did not end under SWA either.
  std::vector<ControlLoss> out_of_control_at_end;
  // Said last with a FAIL (record::Scoring::failure_hint): what in the world the reasons above come from.
  std::string failure_hint;
};

Verdict judge(const VerdictInput& input);

const char* toString(Outcome outcome);                         // "PASS", "FAIL", "INCOMPLETE"
std::optional<Outcome> parseOutcome(const std::string& text);  // the inverse
// The exit status that carries it: 0 PASS, 1 FAIL, 3 INCOMPLETE (2 is a bad command line or input).
int exitCode(Outcome outcome);
// "PASS", or "FAIL: reason; reason" (the report's verdict line).
std::string verdictText(const Verdict& verdict);

}  // namespace swa::record

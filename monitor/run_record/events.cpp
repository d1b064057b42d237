#include "swa/run_record/events.h"

namespace swa::record {

EventRecord eventOf(const sim::Event& e) {
  EventRecord r;
  r.t_s = static_cast<double>(e.stamp_ns) * 1e-9;
  r.uav = e.uav;
  switch (e.kind) {
    case sim::EventKind::kGnssLost:
      r.kind = event_kind::kGnssLost;
      r.text = "GNSS lost";
      break;
    case sim::EventKind::kGnssRestored:
      r.kind = event_kind::kGnssRestored;
      r.text = "GNSS restored";
      break;
    case sim::EventKind::kCollision:
      r.kind = event_kind::kCollision;
      r.other_uav = e.other_uav;
      r.value = e.value;
      r.text = "collision (value: distance, m)";
      break;
    case sim::EventKind::kFailsafeOn:
      r.kind = event_kind::kFailsafe;
      r.value = e.value;
      r.text = "failsafe on (value: setpoint age, s)";
      break;
    case sim::EventKind::kFailsafeOff:
      r.kind = event_kind::kFailsafe;
      r.text = "failsafe off";
      break;
  }
  return r;
}

}  // namespace swa::record

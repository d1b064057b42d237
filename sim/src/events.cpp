#include "swa/sim/events.h"

namespace swa::sim {

EventRecord eventOf(const Event& e) {
  EventRecord r;
  r.t_s = static_cast<double>(e.stamp_ns) * 1e-9;
  r.uav = e.uav;
  switch (e.kind) {
    case EventKind::kGnssLost:
      r.kind = event_kind::kGnssLost;
      r.text = "GNSS lost";
      break;
    case EventKind::kGnssRestored:
      r.kind = event_kind::kGnssRestored;
      r.text = "GNSS restored";
      break;
    case EventKind::kCollision:
      r.kind = event_kind::kCollision;
      r.other_uav = e.other_uav;
      r.value = e.value;
      r.text = "collision (value: distance, m)";
      break;
    case EventKind::kFailsafeOn:
      r.kind = event_kind::kFailsafe;
      r.value = e.value;
      r.text = "failsafe on (value: setpoint age, s)";
      break;
    case EventKind::kFailsafeOff:
      r.kind = event_kind::kFailsafe;
      r.text = "failsafe off";
      break;
  }
  return r;
}

}  // namespace swa::sim

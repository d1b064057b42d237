#pragma once
// What a stand-in autopilot (px4_standin.h, ardupilot_standin.h) says happened, for the scenario's events: whether SWA
// lost or regained control of the vehicle through it (the verdict judges a run whose vehicle ends out of SWA's
// control), and a text for the logs.

#include <string>

namespace swa::sim {

struct StandinEvent {
  enum class Control {
    kNone,      // news only (a setpoint that is not simulated, ...)
    kLost,      // the vehicle no longer flies the bridge's commands (a failsafe, a stop for silence)
    kRegained,  // it flies them again (offboard or GUIDED engaged, commands again)
  };
  Control control = Control::kNone;
  std::string text;
};

}  // namespace swa::sim

#pragma once
// Command line of swa_px4_bridge. Parsing is separate from main() so it can be tested; every problem is reported at
// once.

#include <optional>
#include <string>

#include "swa/autopilot/ardupilot.h"
#include "swa/autopilot/bridge_core.h"
#include "swa/autopilot/navsat.h"
#include "swa/autopilot/odometry_feed.h"
#include "swa/px4/release.h"

namespace swa::bridge_node {

enum class AutopilotKind { kPx4, kArdupilot };

struct BridgeOptions {
  int id = -1;                                     // --id I (required)
  AutopilotKind autopilot = AutopilotKind::kPx4;   // --autopilot px4|ardupilot
  std::optional<std::string> px4_namespace;        // --px4-namespace NS (default px4_<I>; "" = none)
  px4::Release px4_release = px4::kNewestRelease;  // --px4-release R
  bool px4_release_given = false;
  std::optional<std::string> ap_namespace;  // --ap-namespace NS (default ap/v<I+1>)
  // --ap-quaternion auto|ros|wxyz; nullopt: auto (decided from gravity, quaternion_order.h)
  std::optional<ardupilot::QuaternionLayout> ap_quaternion;
  bool no_gnss = false;                   // --no-gnss: leave swa/uav<I>/gnss to another source
  ardupilot::NavSatForwardConfig navsat;  // --gnss-silence-s (ArduPilot)
  bool gnss_silence_given = false;
  int target_system = 0;                   // --target-system N: VehicleCommand.target_system (0: any)
  autopilot::BridgeConfig core;            // --stale-after-s, --agent-lost-after-s, ... and --engage
  autopilot::OdometryFeedConfig odometry;  // --odometry gnss-loss|always|off
  bool no_odometry = false;                // --no-odometry: --odometry off
  std::optional<std::string> domain;       // --domain D (else SWA_DOMAIN, else 0)
  std::string summary_out;                 // --summary-out FILE: counters and latency as JSON at exit
  bool help = false;
};

// Accepts "--opt value" and "--opt=value". Throws std::invalid_argument listing every problem, one per line.
BridgeOptions parseBridgeOptions(const std::vector<std::string>& args);
std::string bridgeUsage();

// The PX4 namespace the bridge uses: --px4-namespace, or px4_<I>.
std::string px4Namespace(const BridgeOptions& o);
// ArduPilot's: --ap-namespace, or ap/v<I+1>.
std::string apNamespace(const BridgeOptions& o);

}  // namespace swa::bridge_node

#include "bridge_options.h"

#include "swa/app/cli.h"
#include "swa/app/number.h"
#include "swa/dds/deployment.h"
#include "swa/dds/naming.h"
#include "swa/dds/options.h"
#include "swa/dds/topics.h"
#include "swa/px4/release.h"

namespace swa::bridge_node {
namespace {

constexpr int kMaxUavId = 9999;

const char* const kDetails = R"(Runs on the drone beside swa_agent --id I (same domain, same SWA_SWARM /
SWA_NAMING).

With --autopilot px4 (the default): PX4's uXRCE-DDS agent puts PX4's topics on the same DDS domain under the
namespace NS (uxrce_dds_client start -n NS). --px4-release must be the vehicle's: v1.16 changed vehicle_status's
layout and renamed its topic vehicle_status_v1, and a bridge of another release would never hear the vehicle's
state.
Reads
  rt/NS/fmu/out/vehicle_attitude
      -> swa/uav<I>/imu (roll, pitch, heading in SWA's convention, stamped with PX4's timestamp: stamp the
      detections on the same clock)
  rt/NS/fmu/out/vehicle_status (vehicle_status_v1 from v1.16)
      armed, nav_state (logged, and for --engage)
  rt/NS/fmu/out/vehicle_command_ack
      the answers to --engage's requests (logged)
  rt/NS/fmu/out/vehicle_gps_position, vehicle_local_position
      -> swa/uav<I>/gnss: valid while the fix is 3D or better and PX4 says xy_valid; the loss (and the regain) at
      once, valid fixes at 10 Hz; position = PX4's local x, y turned to east, north; std = eph. From v1.17 the
      second topic is vehicle_local_position_v1.
  swa/uav<I>/cmd_vel
      the agent's velocity setpoints (one writer at a time)
  swa/uav<I>/state
      the agent's own estimate, for --odometry
Writes
  rt/NS/fmu/in/vehicle_visual_odometry
      --odometry (by default while the agent has no GNSS): the agent's position and velocity as external vision,
      NED, at the agent's state rate (10 Hz), stamped on PX4's clock, reset_counter bumped when the agent's estimate
      restarts; EKF2 fuses it with EKF2_EV_CTRL = 5 (deploy/README.md, "External odometry")
  rt/NS/fmu/in/trajectory_setpoint
      velocity in NED, the yaw rate as yawspeed (clockwise: the opposite sign of SWA's); position, acceleration, yaw
      NaN; vertical speed 0
  rt/NS/fmu/in/offboard_control_mode
      velocity control, with every setpoint and at least every 50 ms
  rt/NS/fmu/in/vehicle_command
      only with --engage: arm, then offboard mode
  swa/uav<I>/bridge_state
      diagnostics: link state, PX4's arming and mode, counters, last event
The offboard stream: every command the agent sends is sent on at once. A command older than --stale-after-s (on
PX4's clock) is replaced by zero velocity and yawspeed (the heading held); after --agent-lost-after-s without one,
or --attitude-lost-after-s without attitude from PX4, the stream stops and PX4's own offboard-loss failsafe
(COM_OF_LOSS_T, COM_OBL_RC_ACT) takes over. Commands answering samples from before this bridge started are
ignored. It never arms or changes the flight mode unless given --engage (bench tests, the simulator). Every state
change is logged and published. With --no-gnss the bridge leaves swa/uav<I>/gnss alone (your own GNSS source
publishes it, or none).

With --autopilot ardupilot (AP_DDS, Copter 4.5+; its Micro XRCE-DDS agent on the same domain):
Reads
  rt/NS/imu/experimental/data
      -> swa/uav<I>/imu (the orientation, FRD -> NED as PX4's, read in the field order of --ap-quaternion; stamped
      with the message's time)
  rt/NS/status
      armed, mode (logged, and for --engage; GUIDED = 4)
  rr/NS/arm_motorsReply, rr/NS/mode_switchReply
      the answers to --engage's requests (logged)
  rt/NS/navsat
      -> swa/uav<I>/gnss (not with --no-gnss): valid while ArduPilot reports a fix (status >= 0); lost when it
      reports none or sends no fix for --gnss-silence-s of its IMU's time (it goes silent when its GPS is unhealthy
      or has no new fix); position = latitude and longitude in metres east and north of the first fix
Writes
  rt/NS/cmd_vel
      TwistStamped in frame "map": ENU velocity, angular.z the yaw rate (counter-clockwise, SWA's sense), stamped
      with the answered sample's time
  rt/NS/tf
      --odometry: the agent's position as an "odom" -> "base_link" transform (north, west, up; the vehicle's
      attitude), stamped 0: ArduPilot fuses it as current less VISO_DELAY_MS (VISO_TYPE 1, EK3 source set 2 =
      external navigation: deploy/README.md, "External odometry")
  rq/NS/arm_motorsRequest, rq/NS/mode_switchRequest
      only with --engage: arm, then GUIDED
The same rules as for PX4, but ArduPilot has no heartbeat: when the stream stops, its GUIDED velocity timeout
(GUID_TIMEOUT) stops the vehicle. ArduPilot accepts velocity commands only when armed and in GUIDED.)";

app::Cli makeCli(BridgeOptions& o) {
  app::Cli cli("swa_px4_bridge", "the autopilot bridge of one UAV: PX4 " + px4::releaseList() +
                                     " (uXRCE-DDS topics) or ArduPilot (AP_DDS) <-> its swa_agent.");
  cli.usage(
      "swa_px4_bridge --id I [--autopilot px4|ardupilot] [--px4-release R] [--px4-namespace NS] [--engage] "
      "[--domain D] [options]");
  cli.details(kDetails);
  cli.integer("--id", "I", o.id, 0, kMaxUavId, "a UAV id", "UAV index (its agent's --id); participant swa_bridge_<I>");
  cli.required("--id");
  cli.value(
      "--autopilot", "A",
      [&o](const std::string& v, app::Problems& problems) {
        if (v == "px4") {
          o.autopilot = AutopilotKind::kPx4;
        } else if (v == "ardupilot") {
          o.autopilot = AutopilotKind::kArdupilot;
        } else {
          problems.push_back("--autopilot '" + v + "': px4 or ardupilot");
        }
      },
      "the vehicle's autopilot: px4 (default; uXRCE-DDS) or ardupilot (AP_DDS, Copter 4.5+)");
  cli.value(
      "--px4-namespace", "NS",
      [&o](const std::string& v, app::Problems& problems) {
        if (!v.empty()) {
          if (const auto problem = dds::rosNamespaceProblem(v)) problems.push_back("--px4-namespace " + *problem);
        }
        o.px4_namespace = dds::normalRosNamespace(v);
      },
      "PX4's ROS namespace (default px4_<I>, what swa_sim's PX4 stand-in uses; '' for none)");
  cli.value(
      "--px4-release", "R",
      [&o](const std::string& v, app::Problems& problems) {
        o.px4_release_given = true;
        if (const std::optional<px4::Release> r = px4::parseRelease(v)) {
          o.px4_release = *r;
        } else {
          problems.push_back("--px4-release '" + v + "': not a supported PX4 release (" + px4::releaseList() + ")");
        }
      },
      std::string("the vehicle's PX4 release: ") + px4::releaseList() + " (default " +
          px4::releaseName(px4::kNewestRelease) + "; a patch release such as 1.16.1 is its minor's)");
  cli.value(
      "--ap-namespace", "NS",
      [&o](const std::string& v, app::Problems& problems) {
        if (const auto problem = dds::rosNamespaceProblem(v)) problems.push_back("--ap-namespace " + *problem);
        o.ap_namespace = dds::normalRosNamespace(v);
      },
      "ArduPilot's ROS namespace (default ap/v<I+1>: AP_DDS with DDS_USE_NS 1 and MAV_SYSID I+1, what swa_sim's "
      "ArduPilot stand-in uses; 'ap' for a vehicle without DDS_USE_NS)");
  cli.value(
      "--ap-quaternion", "L",
      [&o](const std::string& v, app::Problems& problems) {
        if (v == "auto") {
          o.ap_quaternion.reset();
        } else if (const auto layout = ardupilot::parseQuaternionLayout(v)) {
          o.ap_quaternion = *layout;
        } else {
          problems.push_back("--ap-quaternion '" + v + "': auto, ros or wxyz");
        }
      },
      "how ArduPilot fills the IMU message's orientation: ros (x, y, z, w as the message defines), wxyz (AP_DDS of "
      "2024 writes w, x, y, z into x, y, z, w) or auto (default): decided from the message's gravity while the "
      "vehicle reports itself disarmed, nothing forwarded until then; a level vehicle facing north or south cannot "
      "tell, and a bridge started in flight needs ros or wxyz (deploy/README.md, \"Flying ArduPilot\")");
  cli.integer("--target-system", "N", o.target_system, 0, 255, "a MAVLink system id",
              "VehicleCommand.target_system of --engage's requests (0: whichever vehicle reads NS)");
  cli.real("--stale-after-s", "T", o.core.stale_after_s, 0.01, 10.0, "a time in seconds",
           "a command older than this (the vehicle's clock) becomes zero velocity");
  cli.real("--agent-lost-after-s", "T", o.core.agent_lost_after_s, 0.02, 60.0, "a time in seconds",
           "no command this long: the stream stops");
  cli.real("--attitude-lost-after-s", "T", o.core.attitude_lost_after_s, 0.02, 60.0, "a time in seconds",
           "no attitude from the vehicle this long (local clock): the stream stops");
  cli.real("--heartbeat-period-s", "T", o.core.heartbeat_period_s, 0.005, 0.1, "a period in seconds",
           "PX4: offboard_control_mode at least this often while streaming (at most 0.1: at least 10 Hz)");
  cli.real("--max-speed-mps", "V", o.core.max_speed_mps, 0.1, 50.0, "a speed in m/s",
           "commands faster than this are clamped (and counted)");
  cli.real("--max-yaw-rate-radps", "W", o.core.max_yaw_rate_radps, 0.01, 10.0, "a rate in rad/s",
           "commanded yaw rates beyond this are clamped (and counted)");
  cli.flag("--no-gnss", o.no_gnss,
           "do not forward the autopilot's GNSS fix and its loss to swa/uav<I>/gnss (another source publishes it)");
  cli.value(
      "--gnss-silence-s", "T",
      [&o](const std::string& v, app::Problems& problems) {
        o.gnss_silence_given = true;
        if (const std::optional<double> t = app::parseReal(v, 0.05, 10.0)) {
          o.navsat.silence_s = *t;
        } else {
          problems.push_back("--gnss-silence-s '" + v + "': a time in seconds in [0.05, 10]");
        }
      },
      "ArduPilot: no fix on navsat for this long (its IMU's time) is a GNSS loss (default 0.5: a GPS at 5 Hz or "
      "more; above 1 for firmware that sends navsat at 1 Hz)");
  cli.choice(
      "--odometry", "WHEN", {"gnss-loss", "always", "off"},
      [&o](std::size_t k) {
        o.odometry.mode = k == 0   ? autopilot::OdometryMode::kWhileGnssLost
                          : k == 1 ? autopilot::OdometryMode::kAlways
                                   : autopilot::OdometryMode::kOff;
      },
      "when the agent's estimate goes to the autopilot as external odometry, which keeps its estimator valid without "
      "GNSS: gnss-loss (default: while the agent has no GNSS, so the autopilot's own GNSS is never fought), always, "
      "or off (a real autopilot then leaves SWA's control seconds after GNSS is lost)");
  cli.flag("--no-odometry", o.no_odometry, "the same as --odometry off");
  cli.flag("--engage", o.core.engage,
           "arm and switch to PX4's offboard or ArduPilot's GUIDED once the agent's stream has run for 1 s (bench "
           "tests, simulation; "
           "never on a flight without a pilot who can take over)");
  cli.domain(o.domain, dds::kMaxDomainId);
  cli.path("--summary-out", "FILE", o.summary_out,
           "at exit, the counters and the latency (attitude in -> setpoint out, the agent's part, the bridge's part; "
           "p50 / p99) as JSON");
  cli.footer(R"(Runs until SIGINT or SIGTERM, then deletes its DDS entities (the offboard stream stops) and exits 0.
Exit status: 0 stopped by a signal; 1 DDS failure (also: security credentials refused); 2 bad arguments (nothing
started); 3 refused: an older swa_px4_bridge with this --id runs in this swarm; 70 Fast DDS stuck inside its
participant (deleting it took over 12 s): restart the bridge.

)" + dds::environmentHelp());
  return cli;
}

void finish(BridgeOptions& o, const app::Cli&, app::Problems& problems) {
  if (o.no_odometry) o.odometry.mode = autopilot::OdometryMode::kOff;
  if (o.core.stale_after_s >= o.core.agent_lost_after_s) {
    problems.push_back("--stale-after-s must be below --agent-lost-after-s");
  }
  if (o.autopilot == AutopilotKind::kArdupilot) {
    o.core.autopilot = autopilot::ardupilotAutopilot();
    if (o.px4_namespace || o.px4_release_given || o.target_system != 0) {
      problems.push_back(
          "--px4-namespace, --px4-release and --target-system are PX4's: not with --autopilot ardupilot");
    }
  } else if (o.ap_namespace || o.gnss_silence_given) {
    problems.push_back("--ap-namespace and --gnss-silence-s are ArduPilot's: add --autopilot ardupilot");
  }
}

}  // namespace

BridgeOptions parseBridgeOptions(const std::vector<std::string>& args) {
  return app::parseOptions<BridgeOptions>(args, makeCli, finish);
}

std::string bridgeUsage() { return app::helpText(makeCli); }

std::string px4Namespace(const BridgeOptions& o) { return o.px4_namespace.value_or(dds::topics::px4Namespace(o.id)); }

std::string apNamespace(const BridgeOptions& o) { return o.ap_namespace.value_or(dds::topics::apNamespace(o.id)); }

}  // namespace swa::bridge_node

#include "replay_options.h"

#include <stdexcept>
#include <string>

#include "swa/app/cli.h"
#include "swa/dds/deployment.h"
#include "swa/dds/options.h"

namespace swa::replay {
namespace {

const char* const kDetails =
    R"(FILE.mcap (the first argument) is a recording of swa_launch --record or swa_monitor --record.

--check  re-runs the agent core in this process on the recorded inputs of every UAV (or --uav I): IMU, detections
  and GNSS in the order swa_agent processes them in a lockstep run (by stamp; at equal stamps IMU, detections,
  GNSS), with the parameters the run was flown with (stored in the recording; --scenario FILE instead, --set on
  top), and compares each command with the one the agent sent, byte for byte. With the recorded parameters a
  lockstep run replays IDENTICAL: a regression test from any recorded flight. With other ones it says where the
  commands change and by how much. A realtime recording on a loaded host can lack commands (the monitor missed
  them): the verdict is then INCOMPLETE RECORDING, not DIFFERENT. No DDS.

Without --check it re-publishes the recorded inputs on DDS as the simulator did, on the same topics and QoS
(SWA_NAMING, SWA_SWARM apply): every UAV's imu, detections and gnss, and with all UAVs also swa/truth, swa/events
and swa/clock, so agents (started with other parameters, say) and swa_monitor run on the recorded data. It waits
(--wait-s) until every replayed UAV's IMU, and with all UAVs swa/truth, has a reader, then publishes at --speed.
--lockstep: after the samples of each stamp, waits for every replayed agent's answer to its IMU sample and for its
acknowledgment of the detections and GNSS fix (as the lockstep simulator does), which makes a fresh agent's commands
reproducible even over a lossy network; the answers are compared with the recorded commands and counted.)";

app::Cli makeCli(ReplayOptions& o) {
  app::Cli cli("swa_replay", "replays a recorded run into agents (DDS), or re-runs the agents' core on it (--check).");
  cli.usage(R"(swa_replay FILE.mcap --check [--uav I] [--scenario FILE] [--set key=value]...
       swa_replay FILE.mcap [--uav I] [--speed X] [--lockstep] [--domain D] [--wait-s S])");
  cli.details(kDetails);
  cli.value(
      "--uav", "I",
      [&o](const std::string& v, app::Problems& p) {
        try {
          std::size_t used = 0;
          const int i = std::stoi(v, &used);
          if (used != v.size() || i < 0 || i > 100'000) throw std::invalid_argument(v);
          o.uav = i;
        } catch (const std::exception&) {
          p.push_back("--uav '" + v + "' is not a UAV index in [0, 100000]");
        }
      },
      "only this UAV (default: every UAV of the recording)");
  cli.flag("--check", o.check, "re-run the agent core in-process and compare its commands (see below)");
  cli.real("--speed", "X", o.speed, 0.0, 1000.0, "a speed factor",
           "recorded seconds per wall second; 0: as fast as possible (with --lockstep: as fast as the agents answer)");
  cli.flag("--lockstep", o.lockstep, "wait for each replayed agent's answer to each IMU sample (see below)");
  cli.scenario(o.scenario_path, "--check: the parameters to run the agents with, instead of the recorded ones");
  cli.overrides(o.overrides,
                "--check: on top of the recorded (or --scenario) parameters, e.g. agent.formation.radius_m=12");
  cli.domain(o.domain, dds::kMaxDomainId);
  cli.real("--wait-s", "S", o.wait_s, 0.0, 3600.0, "a wall time in seconds",
           "longest wait for the agents' IMU readers before replaying (then it replays anyway)");
  cli.footer(R"(Exit status: 0 replayed (--check / --lockstep: every command identical to the recorded one);
             1 commands differ or are missing; 2 bad arguments, an unreadable or malformed recording, bad parameters.

)" + dds::environmentHelp());
  return cli;
}

}  // namespace

ReplayOptions parseReplayOptions(const std::vector<std::string>& args) {
  // FILE is the first argument; the rest are options.
  std::vector<std::string> rest = args;
  std::string file;
  if (!rest.empty() && rest.front().rfind("-", 0) != 0) {
    file = rest.front();
    rest.erase(rest.begin());
  }
  return app::parseOptions<ReplayOptions>(
      rest, makeCli, [&file](ReplayOptions& o, const app::Cli& cli, app::Problems& problems) {
        o.file = file;
        if (o.help) return;
        if (o.file.empty()) problems.push_back("the recording FILE.mcap (first argument) is missing");
        if (o.check) {
          for (const char* live : {"--speed", "--lockstep", "--domain", "--wait-s"}) {
            if (cli.given(live)) problems.push_back(std::string(live) + " replays on DDS: not with --check");
          }
        } else {
          for (const char* offline : {"--scenario", "--set"}) {
            if (cli.given(offline)) {
              problems.push_back(std::string(offline) + " applies to --check (agents replayed into get their own)");
            }
          }
          if (o.speed == 0.0 && !o.lockstep) problems.push_back("--speed 0 needs --lockstep (nothing else paces it)");
        }
      });
}

std::string replayUsage() { return app::helpText(makeCli); }

}  // namespace swa::replay

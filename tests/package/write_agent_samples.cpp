// write_agent_samples: recorded samples for agent/examples/embed_agent, and the commands SWA's own agent core gives
// for them (issue #47). It runs a scenario in-process (the world and an agent per UAV, as swa_batch does), writes
// one UAV's samples in the example's format, and feeds the same samples, as written, to a fresh agent with the
// default configuration, as the example does: its commands are what the example, built against an installed SWA,
// must print bit for bit.
//   write_agent_samples SCENARIO SECONDS UAV SAMPLES_OUT COMMANDS_OUT
#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "swa/agent/agent.h"
#include "swa/agent/feed.h"
#include "swa/sim/scenario_io.h"
#include "swa/sim/world.h"

namespace swa {
namespace {

// What the example's format keeps of a sample: no accelerometer, no per-detection covariance.
agent::ImuSample asWritten(const agent::ImuSample& imu) {
  return agent::ImuSample(imu.stamp_ns, imu.roll_rad, imu.pitch_rad, imu.heading_rad);
}
agent::DetectionSet asWritten(agent::DetectionSet set) {
  for (agent::Detection& d : set.detections) d.covariance_m2.reset();
  return set;
}

void write(std::FILE* out, const agent::ImuSample& s) {
  std::fprintf(out, "imu %lld %.17g %.17g %.17g\n", static_cast<long long>(s.stamp_ns), s.roll_rad, s.pitch_rad,
               s.heading_rad);
}
void write(std::FILE* out, const agent::DetectionSet& s) {
  std::fprintf(out, "det %lld %zu", static_cast<long long>(s.stamp_ns), s.detections.size());
  for (const agent::Detection& d : s.detections) {
    std::fprintf(out, " %d %.17g %.17g", d.target_id, d.position_body_m.x(), d.position_body_m.y());
  }
  std::fprintf(out, "\n");
}
void write(std::FILE* out, const agent::GnssSample& s) {
  std::fprintf(out, "gnss %lld %d %.17g %.17g %.17g\n", static_cast<long long>(s.stamp_ns), s.valid ? 1 : 0,
               s.position_m.x(), s.position_m.y(), s.std_m);
}

std::FILE* openOut(const std::string& path) {
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (f == nullptr) throw std::runtime_error("cannot write " + path);
  return f;
}

int run(const std::vector<std::string>& args) {
  if (args.size() != 5) {
    std::fprintf(stderr, "usage: write_agent_samples SCENARIO SECONDS UAV SAMPLES_OUT COMMANDS_OUT\n");
    return 2;
  }
  sim::Scenario scenario = sim::loadScenario(args[0], {"duration_s=" + args[1]});
  const int uav = std::stoi(args[2]);
  sim::World world(scenario);
  if (uav < 0 || uav >= world.uav_count()) throw std::invalid_argument("no UAV " + args[2] + " in " + args[0]);
  std::vector<agent::Agent> agents(static_cast<std::size_t>(world.uav_count()), agent::Agent(scenario.agent));
  agent::Agent replayed{agent::AgentConfig{}};
  std::FILE* samples = openOut(args[3]);
  std::FILE* commands = openOut(args[4]);
  std::fprintf(samples, "# UAV %d of %s, %s s, written by tests/package/write_agent_samples (main.cpp: the format)\n",
               uav, args[0].c_str(), args[1].c_str());
  while (true) {
    const std::vector<sim::UavSensors>& sensors = world.sensors();
    for (int i = 0; i < world.uav_count(); ++i) {
      const sim::UavSensors& s = sensors[static_cast<std::size_t>(i)];
      if (const auto command = agent::feedInstant(agents[static_cast<std::size_t>(i)], s.imu, s.detections, s.gnss)) {
        world.command(i, *command);
      }
    }
    const sim::UavSensors& s = sensors[static_cast<std::size_t>(uav)];
    std::optional<agent::ImuSample> imu;
    std::optional<agent::DetectionSet> detections;
    if (s.imu) write(samples, *(imu = asWritten(*s.imu)));
    if (s.detections) write(samples, *(detections = asWritten(*s.detections)));
    if (s.gnss) write(samples, *s.gnss);
    if (const auto command = agent::feedInstant(replayed, imu, detections, s.gnss)) {
      std::fprintf(commands, "cmd %lld %.17g %.17g %.17g\n", static_cast<long long>(command->stamp_ns),
                   command->velocity_mps.x(), command->velocity_mps.y(), command->yaw_rate_radps);
    }
    if (world.finished()) break;
    world.step();
  }
  const bool written = std::fclose(samples) == 0 && std::fclose(commands) == 0;
  return written ? 0 : 1;
}

}  // namespace
}  // namespace swa

int main(int argc, char** argv) {
  try {
    return swa::run(std::vector<std::string>(argv + 1, argv + argc));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "write_agent_samples: %s\n", e.what());
    return 1;
  }
}

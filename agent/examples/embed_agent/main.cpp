// embed_agent: SWA's agent in a program of your own, without DDS. It reads recorded samples of one UAV, feeds them to
// swa::agent::Agent one instant at a time (IMU first, then detections, then GNSS: swa/agent/feed.h) and prints the
// velocity command that answers each IMU sample. A line of SAMPLES is one sample ('#' starts a comment):
//   imu  STAMP_NS ROLL PITCH HEADING     attitude, rad (heading counter-clockwise from the stable frame's x)
//   det  STAMP_NS COUNT [ID X Y]...      the neighbours seen, body frame, m (ID -1: a sensor that does not identify)
//   gnss STAMP_NS VALID X Y STD          a position fix in the local frame, m (VALID 0: no fix)
// Printed: cmd STAMP_NS VX VY YAW_RATE (m/s in the stable frame, rad/s), one line per IMU sample.
#include <cstdio>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>

#include <swa/agent/agent.h>
#include <swa/agent/feed.h>

namespace sa = swa::agent;

int main(int argc, char** argv) {
  std::ifstream in(argc == 2 ? argv[1] : "");
  if (!in) {
    std::fprintf(stderr, "usage: embed_agent SAMPLES (a readable file)\n");
    return 2;
  }
  sa::Agent agent{sa::AgentConfig{}};  // the defaults; a node of yours loads its own configuration
  std::optional<sa::ImuSample> imu;
  std::optional<sa::DetectionSet> detections;
  std::optional<sa::GnssSample> gnss;
  auto feed = [&] {
    const auto command = sa::feedInstant(agent, imu, detections, gnss);
    if (command) {
      std::printf("cmd %lld %.17g %.17g %.17g\n", static_cast<long long>(command->stamp_ns), command->velocity_mps.x(),
                  command->velocity_mps.y(), command->yaw_rate_radps);
    }
    imu.reset();
    detections.reset();
    gnss.reset();
  };

  std::string line, kind;
  sa::StampNs stamp = 0, instant = -1;
  for (int n = 1; std::getline(in, line); ++n) {
    std::istringstream s(line);
    if (line.empty() || line[0] == '#') continue;
    s >> kind >> stamp;
    if (stamp != instant) feed();  // a new instant: the last one goes to the agent whole
    instant = stamp;
    if (kind == "imu") {
      imu.emplace().stamp_ns = stamp;
      s >> imu->roll_rad >> imu->pitch_rad >> imu->heading_rad;
    } else if (kind == "det") {
      detections.emplace().stamp_ns = stamp;
      int count = 0;
      s >> count;
      for (int i = 0; i < count && s; ++i) {
        sa::Detection& d = detections->detections.emplace_back();
        s >> d.target_id >> d.position_body_m.x() >> d.position_body_m.y();
      }
    } else if (kind == "gnss") {
      gnss.emplace().stamp_ns = stamp;
      s >> gnss->valid >> gnss->position_m.x() >> gnss->position_m.y() >> gnss->std_m;
    }
    if (!s || (kind != "imu" && kind != "det" && kind != "gnss")) {
      std::fprintf(stderr, "embed_agent: %s:%d: not a sample: %s\n", argv[1], n, line.c_str());
      return 2;
    }
  }
  feed();
  std::fprintf(stderr, "embed_agent: %llu input(s) rejected\n",
               static_cast<unsigned long long>(agent.diagnostics().rejected.total()));
}

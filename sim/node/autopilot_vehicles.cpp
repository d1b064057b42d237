#include "autopilot_vehicles.h"

namespace swa::sim_node {
namespace {

constexpr std::size_t kRecentSamples = 256;  // attitude samples whose stamp an answer can still find

}  // namespace

void RecentSamples::add(agent::StampNs stamp_ns, std::uint32_t seq) {
  samples_.push_back({stamp_ns, seq, false});
  if (samples_.size() > kRecentSamples) samples_.pop_front();
}

std::optional<std::uint32_t> RecentSamples::answer(agent::StampNs stamp_ns) {
  for (Sample& s : samples_) {
    if (s.stamp_ns == stamp_ns && !s.answered) {
      s.answered = true;
      return s.seq;
    }
  }
  return std::nullopt;
}

Answer answerOf(int uav, AutopilotVehicles::Clock::time_point received, const dds::WriterGuid& writer,
                const agent::Vec2& velocity_mps, double yaw_rate_radps, bool velocity_only) {
  Answer a;
  a.uav = uav;
  a.received = received;
  a.writer = writer;
  a.velocity_only = velocity_only;
  a.setpoint.uav_id(static_cast<std::uint32_t>(uav));
  a.setpoint.vx_mps(velocity_mps.x());
  a.setpoint.vy_mps(velocity_mps.y());
  a.setpoint.yaw_rate_radps(yaw_rate_radps);
  return a;
}

void markAnswered(Answer& a, agent::StampNs stamp_ns, std::uint32_t seq) {
  a.setpoint.answered_stamp_ns(stamp_ns);
  a.setpoint.header().stamp_ns(stamp_ns);
  a.setpoint.answered_seq(seq);
}

void commandWorld(sim::World& world, int uav, const agent::Vec2& velocity_mps, bool following, double yaw_rate_radps) {
  agent::VelocityCommand command;
  command.stamp_ns = world.time_ns();
  command.velocity_mps = velocity_mps;
  command.yaw_rate_radps = following ? yaw_rate_radps : 0.0;
  command.fresh = true;
  world.command(uav, command);
}

}  // namespace swa::sim_node

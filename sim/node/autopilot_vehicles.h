#pragma once
// swa_sim's UAVs as autopilots (vehicle.interface = px4 or ardupilot): what the simulator's ports (sim_ports.h) ask of
// either stand-in (px4_vehicles.h, ardupilot_vehicles.h). For each UAV the simulator publishes the autopilot's attitude
// (its IMU sample in the autopilot's message) and state, reads what one bridge per UAV sends, and lets a pure stand-in
// (swa/sim/px4_standin.h, ardupilot_standin.h) decide what the vehicle flies. A command stamped with a recent attitude
// sample's time is that sample's answer: it goes to the drivers' lockstep / realtime rules like an agent's cmd_vel
// (answer.h); the bridge's own commands (zero velocity for a stale agent) and requests go to the stand-in at once.

#include <chrono>
#include <cstdint>
#include <deque>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "answer.h"
#include "swa/agent/samples.h"
#include "swa/dds/participant.h"
#include "swa/px4/frames.h"
#include "swa/sim/standin_event.h"
#include "swa/sim/world.h"

namespace swa::sim_node {

class AutopilotVehicles {
 public:
  using Clock = std::chrono::steady_clock;
  // Whether a command comes from its UAV's one commander (command_gate.h), counted by the caller.
  using AdmitFn = std::function<bool(const Answer&)>;
  // A stand-in's event (failsafe, engaged, ...): UAV, value, what it means for SWA's control and its text (the text
  // names the stand-in).
  using EventFn = std::function<void(int uav, double value, const sim::StandinEvent& event)>;

  virtual ~AutopilotVehicles() = default;

  // UAV `uav`'s autopilot endpoints the bridge has not matched yet, appended to `missing`.
  virtual void unmatched(int uav, std::vector<std::string>& missing) const = 0;
  // UAV `uav`'s IMU sample as its autopilot's attitude message. False if the middleware refused it.
  virtual bool publishAttitude(int uav, const agent::ImuSample& s, std::uint32_t seq) = 0;
  // UAV `uav`'s GNSS sample as its autopilot reports it (vehicle.gnss_source = autopilot). False if refused (or the
  // source is not the autopilot).
  virtual bool publishGnss(int uav, const agent::GnssSample& g) = 0;
  // The newest attitude of `uav` once more. An autopilot streams its attitude whatever happens; in lockstep the
  // simulated time stands still while the simulator waits for an answer, so the stand-in repeats the sample: a
  // best-effort sample lost on the way (or sent before the bridge's reader matched) would otherwise stall the run.
  virtual void repeatAttitude(int uav) = 0;
  // Waits up to `wait` for what the bridges sent, at simulation time `now`: answers are appended to `answers`; the
  // rest goes to the stand-ins (the bridges' own commands only if `admit`).
  virtual void drain(std::vector<Answer>& answers, Clock::duration wait, agent::StampNs now, const AdmitFn& admit) = 0;
  // An answer the driver applies: the vehicle's newest command.
  virtual void apply(const Answer& a) = 0;
  // Before the world steps from `now`: each vehicle's decision commanded to the world, its state when it changed, the
  // stand-ins' events.
  virtual void step(sim::World& world, const EventFn& event) = 0;
  // Where UAV `uav`'s commands arrive (for the logs).
  virtual std::string commandTopic(int uav) const = 0;
};

// The attitude samples one vehicle published recently, which an answer names by their stamp.
class RecentSamples {
 public:
  void add(agent::StampNs stamp_ns, std::uint32_t seq);
  // The seq of the unanswered sample stamped `stamp_ns`, now marked answered; nullopt if there is none (the bridge's
  // own command, or a repeat).
  std::optional<std::uint32_t> answer(agent::StampNs stamp_ns);

 private:
  struct Sample {
    agent::StampNs stamp_ns = 0;
    std::uint32_t seq = 0;
    bool answered = false;
  };
  std::deque<Sample> samples_;
};

// One vehicle's attitude stream, PX4's or ArduPilot's message: what it published recently (an answer names a sample by
// its stamp) and the newest, which repeat() sends again.
template <class Message>
struct AttitudeStream {
  dds::Writer<Message> writer;
  std::optional<Message> last;
  RecentSamples published;
  // The attitude the autopilot reports: the accelerometer part's (its estimate of the true attitude) when the agents
  // fuse the accelerometer, else the tilt's (whose error model is the tilt source's, imu_model.h), so that an agent
  // behind a bridge reads what one reading the simulator directly does.
  bool accelerometer_attitude = false;

  // The IMU sample `s` as `make(timestamp_us, quaternion)`, the autopilot's message. False when the sample has no
  // autopilot timestamp (negative) or the middleware refused it.
  template <class Make>
  bool publish(const agent::ImuSample& s, std::uint32_t seq, Make make) {
    const std::optional<std::uint64_t> timestamp = px4::timestampUsOf(s.stamp_ns);
    if (!timestamp) return false;
    const bool acc = accelerometer_attitude && s.accelerometer;
    const px4::Quaternion q = px4::quaternionOf(px4::px4Euler(
        {acc ? s.accelerometer->roll_rad : s.roll_rad, acc ? s.accelerometer->pitch_rad : s.pitch_rad, s.heading_rad}));
    last = make(*timestamp, q);
    published.add(s.stamp_ns, seq);
    return writer.write(*last);
  }
  void repeat() {
    if (last) writer.write(*last);
  }
};

// A vehicle's command as the drivers take it: UAV, arrival, writer and the setpoint in the stable frame (the yaw rate
// already the world's, world_command.h), and then, if it answers a sample, which.
Answer answerOf(int uav, AutopilotVehicles::Clock::time_point received, const dds::WriterGuid& writer,
                const agent::Vec2& velocity_mps, double yaw_rate_radps, bool velocity_only);
void markAnswered(Answer& a, agent::StampNs stamp_ns, std::uint32_t seq);

// What a vehicle flies this step, commanded to the world: its decision's velocity, and its yaw rate while it follows
// the bridge (holding: the heading too).
void commandWorld(sim::World& world, int uav, const agent::Vec2& velocity_mps, bool following, double yaw_rate_radps);

// One vehicle's part of step(), either stand-in: its GNSS as the world has it now, its decision commanded to the
// world with the yaw rate of its newest command, and its events raised as "`who`: text" with the stand-in's value.
template <class Standin>
void stepVehicle(sim::World& world, int uav, Standin& standin, double yaw_rate_radps, const std::string& who,
                 const AutopilotVehicles::EventFn& event) {
  standin.gnss(world.time_ns(), world.truth().at(static_cast<std::size_t>(uav)).gnss_valid);
  const typename Standin::Decision d = standin.step(world.time_ns());
  commandWorld(world, uav, d.velocity_mps, d.following, yaw_rate_radps);
  for (sim::StandinEvent& e : standin.takeEvents()) {
    e.text = who + ": " + e.text;
    event(uav, standin.eventValue(), e);
  }
}

}  // namespace swa::sim_node

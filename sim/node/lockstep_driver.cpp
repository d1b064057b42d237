#include "lockstep_driver.h"

#include <algorithm>
#include <cstdio>

#include "swa/sim/events.h"
#include "swa/sim/timing.h"

namespace swa::sim_node {
namespace {
// How many steps the monitors may fall behind in lockstep (awaitSensorAcks): the truth period, 0.1 s of simulated time.
constexpr std::int64_t kMonitorLagSteps = 10;
// How often a step that waits longer says so, with its clock tick again: the agents' silence watches take inputs
// silent for 6 s with their writers matched for a broken channel, unless the world waits (agent/node/world_pause.h).
constexpr auto kWaitingTickPeriod = std::chrono::seconds(1);
}  // namespace

LockstepDriver::LockstepDriver(const DriverContext& context) : Driver(context), lockstep_(n_) {}

void LockstepDriver::run() {
  const double startup_s = std::max(options_.agent_timeout_s, options_.startup_timeout_s);
  while (!stop_) {
    ports_.publishStepOutputs(aliveFn());
    lockstep_.begin(ports_.publishSensors(std::nullopt));
    auto published = Clock::now();
    auto ticked = published;
    drain(Clock::duration::zero());  // answers of dead agents are looked at even if nobody is waited for
    // An agent that never answered may still be matching our writers (discovery is not symmetric): it gets the
    // startup timeout, not the agent timeout, for its first answer.
    const double timeout_s = lockstep_.waitingForNewcomer() ? startup_s : options_.agent_timeout_s;
    auto deadline = std::max(Clock::now(), reconnect_grace_until_) + seconds(timeout_s);
    // Checked at least once per step (stepping and publishing take milliseconds), in the answer wait and in the
    // acknowledgment wait: wherever the simulator is stopped, the stall is seen, and the agents it kept from answering
    // get that much longer (a stall seen here may predate the deadline: then they get more than needed, harmless).
    bool checked = false;
    while (!checked || (!lockstep_.complete() && !stop_)) {
      checked = true;
      const auto now = Clock::now();
      const Clock::duration lost = stall_.check(now);
      if (lost > Clock::duration::zero()) {
        deadline += lost;  // the agents had no chance to answer while the simulator did not run
        noteStall(lost, now);
        deadline = std::max(deadline, reconnect_grace_until_ + seconds(timeout_s));
      }
      if (lockstep_.complete() || stop_) break;
      if (now >= deadline) break;
      if (now - published >= kRepeatPeriod) {
        ports_.repeatWhileWaiting(lockstep_.waitingFor());
        published = now;
      }
      if (now - ticked >= kWaitingTickPeriod) {
        ports_.publishClock();
        ticked = now;
      }
      drain(std::min<Clock::duration>({deadline - now, kPollPeriod, kRepeatPeriod}));
    }
    if (stop_) break;
    for (const int i : lockstep_.expire()) {
      ++summary_.agent_dead_events;
      std::fprintf(stderr, "swa_sim: t = %.2f s: agent %d did not answer within %.3f s: dead, UAV %d on failsafe\n",
                   sim::stampSeconds(world_.time_ns()), i, timeout_s, i);
      ports_.publishEvent(sim::event_kind::kAgentDead, i, timeout_s, "no answer within the agent timeout");
    }
    awaitSensorAcks(deadline);
    if (stop_) break;
    if (world_.finished()) break;
    ports_.vehiclesStep();
    world_.step();
  }
}

void LockstepDriver::awaitSensorAcks(Clock::time_point& deadline) {
  // The agent orders its inputs by stamp (sample_order.h), which reproduces the closed loop only if this step's
  // detections and GNSS fix are in its queue before the next step's IMU sample. DDS orders samples per topic, not
  // across topics (a repaired loss on one topic, or another transport path, lets the next IMU overtake them), so
  // wait until each live agent has acknowledged them: an RTPS acknowledgment follows the reader's listener call.
  for (int i = 0; i < n_; ++i) {
    if (!ports_.sideWritten(i) || !lockstep_.alive(i)) continue;
    const bool acknowledged = awaitAck(deadline, [&](double wait_s) {
      return ports_.detectionsAcknowledged(i, wait_s) && ports_.gnssAcknowledged(i, wait_s);
    });
    if (!acknowledged) ++summary_.unacknowledged_sensor_steps;
  }
  // The monitors (every reader of the clock) may fall kMonitorLagSteps steps behind, no more. Nothing else makes the
  // simulator wait for them, and a lockstep run outpaces the wall clock many times: a monitor that lost the CPU for
  // half a second came back to a backlog larger than its transport holds, and its recording lost most of the run's
  // commands (KEEP_LAST 1: a lost one is not repaired) and sensor frames, while its verdict still passed.
  if (world_.step_index() % kMonitorLagSteps == 0 &&
      !awaitAck(deadline, [&](double wait_s) { return ports_.clockAcknowledged(wait_s); })) {
    ++summary_.unacknowledged_clock_steps;
  }
}

bool LockstepDriver::awaitAck(Clock::time_point& deadline, const std::function<bool(double)>& acknowledged) {
  // Bounded by the step's deadline, so a stalled reader costs at most one agent timeout per step. Waited in slices of
  // one poll period, so a stall of the simulator here is seen and moves the deadline like in the answer wait.
  const auto slice_s = [&] {
    const auto left = std::min<Clock::duration>(deadline - Clock::now(), kPollPeriod);
    return std::max(0.0, std::chrono::duration<double>(left).count());
  };
  while (!stop_) {
    if (acknowledged(slice_s())) return true;
    const auto now = Clock::now();
    const Clock::duration lost = stall_.check(now);
    if (lost > Clock::duration::zero()) {
      deadline += lost;
      noteStall(lost, now);
    }
    if (now >= deadline) return false;
  }
  return false;
}

void LockstepDriver::drain(Clock::duration wait) {
  for (const SimPorts::Answer& a : ports_.drain(wait)) {
    switch (lockstep_.onAnswer(a.uav, a.setpoint.answered_stamp_ns())) {
      case Verdict::kApply:
        ports_.apply(a);
        break;
      case Verdict::kRejoin:
        ports_.apply(a);
        ++summary_.agent_rejoined_events;
        std::fprintf(stderr, "swa_sim: t = %.2f s: agent %d answers again: rejoined\n",
                     sim::stampSeconds(world_.time_ns()), a.uav);
        ports_.publishEvent(sim::event_kind::kAgentRejoined, a.uav, 0.0, "answering again");
        break;
      case Verdict::kIgnore:
        ++summary_.ignored_commands;
        break;
    }
  }
}

}  // namespace swa::sim_node

#include "realtime_driver.h"

#include <algorithm>
#include <cstdio>
#include <vector>

#include "swa/sim/events.h"
#include "swa/sim/timing.h"

namespace swa::sim_node {

RealtimeDriver::RealtimeDriver(const DriverContext& context)
    : Driver(context),
      alive_(static_cast<std::size_t>(n_), true),
      last_answer_(static_cast<std::size_t>(n_)),
      last_applied_(static_cast<std::size_t>(n_)) {}

void RealtimeDriver::handshake() {
  // The clock starts once every agent has closed the loop once. Discovery is not symmetric: when the simulator has
  // matched every agent's endpoints, an agent may not have matched the simulator's yet, and samples written meanwhile
  // reach it (TRANSIENT_LOCAL) only once it has, i.e. late. So step 0's samples are published untimed, and pacing
  // starts when each agent has answered them (typically within a few ms), or after the startup timeout (agents still
  // silent are then declared dead by the agent timeout as usual). Step 0 is not in the latency statistics: its answers
  // measure discovery, not the loop.
  const auto t_handshake = Clock::now();
  ports_.timeLatency(false);
  ports_.publishStepOutputs(aliveFn());
  ports_.publishSensors(std::nullopt);
  const auto deadline = t_handshake + seconds(options_.startup_timeout_s);
  const auto everyoneAnswered = [this] {
    return std::all_of(last_applied_.begin(), last_applied_.end(), [](const auto& a) { return a.has_value(); });
  };
  // An autopilot stand-in's attitude is best effort, as the autopilots send it: a bridge that matched the stand-in's
  // writer only after step 0 went out, or lost it on a busy host, never answers, and the clock never starts (seen
  // twice in 110 runs beside a CPU hog: bridge 3 of a realtime run through ArduPilot got its vehicle's status, which
  // is reliable, but no attitude, and no port of it was deaf). So the unanswered UAVs' attitude goes out again, as in
  // lockstep; a bridge that had it forwards a repeat of the same stamp once only.
  auto repeated = Clock::now();
  while (!everyoneAnswered() && !stop_) {
    const auto now = Clock::now();
    if (now >= deadline) break;
    if (now - repeated >= kRepeatPeriod) {
      std::vector<int> unanswered;
      for (int i = 0; i < n_; ++i) {
        if (!last_applied_[static_cast<std::size_t>(i)]) unanswered.push_back(i);
      }
      ports_.repeatWhileWaiting(unanswered);
      repeated = now;
    }
    drain(std::min<Clock::duration>({deadline - now, kPollPeriod, kRepeatPeriod}));
  }
  ports_.timeLatency(true);
  summary_.handshake_s = secondsSince(t_handshake);
  if (!everyoneAnswered() && !stop_) {
    std::fprintf(stderr, "swa_sim: not every agent answered step 0 within %.0f s; starting the clock anyway\n",
                 options_.startup_timeout_s);
  }
}

void RealtimeDriver::run() {
  const double speed = scenario_.clock.speed;
  const agent::StampNs dt_ns = sim::stepPeriodNs(scenario_.dynamics.rate_hz);
  const auto timeout = seconds(options_.agent_timeout_s);
  handshake();

  auto start = Clock::now();
  for (auto& t : last_answer_) t = start;
  const auto scheduledTime = [&](agent::StampNs stamp_ns) {
    return start + seconds(sim::stampSeconds(stamp_ns) / speed);
  };
  // A stall of the simulator itself pauses the simulated world with it (the schedule and every agent's silence
  // move by the time lost), instead of racing through the missed steps and blaming the agents.
  const auto absorbStall = [&](Clock::time_point now) {
    const Clock::duration lost = stall_.check(now);
    if (lost <= Clock::duration::zero()) return;
    start += lost;
    noteStall(lost, now);
    // An answer drained after the stall but before this check is already recent: never move it into the future.
    for (auto& t : last_answer_) t = std::max(std::min(t + lost, now), reconnect_grace_until_);
  };
  stall_.restart(Clock::now());
  while (!world_.finished() && !stop_) {
    absorbStall(Clock::now());
    auto target = scheduledTime(world_.time_ns() + dt_ns);  // the next step
    Clock::time_point last_drain;
    do {
      const auto now = Clock::now();
      absorbStall(now);
      target = scheduledTime(world_.time_ns() + dt_ns);
      last_drain = now;
      drain(now < target ? std::min<Clock::duration>(target - now, kPollPeriod) : Clock::duration::zero());
    } while (Clock::now() < target && !stop_);
    // What the last drain took is applied to this step, however late the simulator itself is: a later answer is not.
    ports_.stepTaken(last_drain);
    absorbStall(Clock::now());
    const auto now = Clock::now();
    for (int i = 0; i < n_; ++i) {
      const auto k = static_cast<std::size_t>(i);
      if (alive_[k] && now - last_answer_[k] > timeout) {
        alive_[k] = false;
        ++summary_.agent_dead_events;
        std::fprintf(stderr, "swa_sim: t = %.2f s: no setpoint from agent %d for %.3f s: dead, UAV %d on failsafe\n",
                     sim::stampSeconds(world_.time_ns()), i, options_.agent_timeout_s, i);
        ports_.publishEvent(sim::event_kind::kAgentDead, i, options_.agent_timeout_s,
                            "no setpoint within the agent timeout");
      }
    }
    if (stop_) break;
    ports_.vehiclesStep();
    world_.step();
    step_lag_.add(wallNs(Clock::now()) - wallNs(target));
    ports_.publishStepOutputs(aliveFn());
    // This step's IMU samples are answered late once the next step is due and taken (stepTaken above).
    ports_.publishSensors(scheduledTime(world_.time_ns() + dt_ns));
  }
  // The last step's samples are judged like every other: collect their answers until they are due.
  if (!stop_) collectLateAnswers(scheduledTime(world_.time_ns() + dt_ns));
}

void RealtimeDriver::drain(Clock::duration wait) {
  const agent::StampNs now_ns = world_.time_ns();
  for (const SimPorts::Answer& a : ports_.drain(wait)) {
    const auto k = static_cast<std::size_t>(a.uav);
    const agent::StampNs answered = a.setpoint.answered_stamp_ns();
    // The latest setpoint wins; answers from the future belong to a previous run (replayed command history).
    const bool newer = !last_applied_[k] || answered > *last_applied_[k];
    if (!newer || answered > now_ns) {
      ++summary_.ignored_commands;
      continue;
    }
    last_applied_[k] = answered;
    last_answer_[k] = Clock::now();
    ports_.apply(a);
    if (!alive_[k]) {
      alive_[k] = true;
      ++summary_.agent_rejoined_events;
      std::fprintf(stderr, "swa_sim: t = %.2f s: agent %d answers again: rejoined\n", sim::stampSeconds(now_ns), a.uav);
      ports_.publishEvent(sim::event_kind::kAgentRejoined, a.uav, 0.0, "answering again");
    }
  }
}

void RealtimeDriver::collectLateAnswers(Clock::time_point until) {
  ports_.stepTaken(until);  // no step follows the last: its answers are late after their due time
  // An answer a little after that is late, as at every other step, not missing: wait a while longer for them.
  const auto end = std::max(until, Clock::now()) + kLastAnswersGrace;
  while (!stop_ && !ports_.newestAnswered()) {
    const auto now = Clock::now();
    if (now >= end) break;
    ports_.drain(std::min<Clock::duration>(end - now, kPollPeriod));  // their latency is recorded; none applied
  }
  ports_.drain(Clock::duration::zero());  // what arrived but was not drained yet
}

}  // namespace swa::sim_node

#include "sim_node.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iomanip>
#include <sstream>
#include <stdexcept>
#include <thread>

#include <swa/msg/ClockPubSubTypes.h>
#include <swa/msg/DetectionsPubSubTypes.h>
#include <swa/msg/GnssFixPubSubTypes.h>
#include <swa/msg/ImuPubSubTypes.h>
#include <swa/msg/ScenarioEventPubSubTypes.h>
#include <swa/msg/SwarmTruthPubSubTypes.h>
#include <swa/msg/VelocitySetpointPubSubTypes.h>

#include "swa/wire/samples.h"
#include "swa/wire/world.h"
#include "swa/dds/shutdown.h"
#include "swa/dds/topics.h"
#include "swa/sim/timing.h"

namespace swa::sim_node {
namespace {

// Longest single wait in a loop, so a signal is noticed quickly.
constexpr auto kPollPeriod = std::chrono::milliseconds(100);
// A loop iteration longer than one poll plus this means the simulator itself did not run (stall_watch.h). Generous:
// on a loaded 2-core machine a wake-up can be a few tens of milliseconds late.
constexpr auto kStallSlack = std::chrono::milliseconds(150);
// A stall this long (beyond the slack) may have outlasted the 4 s participant lease (deploy/dds/profiles.xml) counted
// from the simulator's last announcement (every 1 s): the agents dropped the simulator and must find it again, some by
// re-creating their participant (agent_node.h, peer_book.h). Each then gets kReconnectGrace more for its next answer.
constexpr auto kLeaseLongStall = std::chrono::seconds(3);
constexpr auto kReconnectGrace = std::chrono::seconds(4);
// A UAV's commands may come from another writer once its current one has been silent this long (command_gate.h):
// longer than any pause of a healthy agent (it answers every 10 ms), shorter than the launcher's restart of a crashed
// one (0.5 s back-off plus the start).
constexpr auto kCommandHandover = std::chrono::milliseconds(500);

std::string guidText(const dds::WriterGuid& g) {
  char text[3 * 16 + 1] = {};
  for (std::size_t k = 0; k < g.size(); ++k) std::snprintf(text + 3 * k, 4, k + 1 < g.size() ? "%02x." : "%02x", g[k]);
  return text;
}


const char* clockModeName(sim::ClockMode m) { return m == sim::ClockMode::kLockstep ? "lockstep" : "realtime"; }

std::chrono::steady_clock::duration seconds(double s) {
  return std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(s));
}

double secondsSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

WallNs wallNs(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(t.time_since_epoch()).count();
}

}  // namespace

SimNode::SimNode(const sim::Scenario& scenario, const SimOptions& options, int domain_id,
                 const std::string& profiles_file)
    : scenario_(scenario),
      options_(options),
      world_(scenario),
      n_(world_.uav_count()),
      lockstep_(n_),
      gate_(n_, kCommandHandover),
      stall_(kPollPeriod + kStallSlack),
      latency_(n_),
      rt_alive_(static_cast<std::size_t>(n_), true),
      rt_last_answer_(static_cast<std::size_t>(n_)),
      rt_last_applied_(static_cast<std::size_t>(n_)),
      imu_seq_(static_cast<std::size_t>(n_), 0),
      det_seq_(static_cast<std::size_t>(n_), 0),
      gnss_seq_(static_cast<std::size_t>(n_), 0),
      side_written_(static_cast<std::size_t>(n_), false) {
  if (!options_.truth_out.empty()) {
    truth_csv_.open(options_.truth_out);
    if (!truth_csv_) throw std::runtime_error("cannot write --truth-out " + options_.truth_out);
    truth_csv_ << "step,t_ns,uav,x_m,y_m,vx_mps,vy_mps,ax_mps2,ay_mps2,heading_rad,agent_alive,gnss_valid,failsafe\n";
    truth_csv_ << std::setprecision(17);
  }

  participant_ = std::make_unique<dds::Participant>("swa_sim", domain_id, profiles_file);
  events_ = participant_->writer<msg::ScenarioEventPubSubType>(dds::topics::kEvents, "swa_event_writer");
  truth_ = participant_->writer<msg::SwarmTruthPubSubType>(dds::topics::kTruth, "swa_truth_writer");
  clock_ = participant_->writer<msg::ClockPubSubType>(dds::topics::kClock, "swa_clock_writer");
  for (int i = 0; i < n_; ++i) {
    imu_.push_back(participant_->writer<msg::ImuPubSubType>(dds::topics::imu(i), "swa_sensor_writer"));
    det_.push_back(
        participant_->writer<msg::DetectionsPubSubType>(dds::topics::detections(i), "swa_detections_gnss_writer"));
    gnss_.push_back(
        participant_->writer<msg::GnssFixPubSubType>(dds::topics::gnss(i), "swa_detections_gnss_writer"));
    cmd_.push_back(participant_->readerWithOrigin<msg::VelocitySetpointPubSubType>(
        dds::topics::cmdVel(i), "swa_command_reader", [this, i](msg::VelocitySetpoint&& m, const dds::WriterGuid& w) {
          queue_.push(Answer{i, std::move(m), Clock::now(), w});
        }));
  }
}

SimNode::~SimNode() { participant_.reset(); }

bool SimNode::awaitDiscovery() {
  const auto t0 = Clock::now();
  const auto deadline = t0 + seconds(options_.startup_timeout_s);
  std::fprintf(stderr, "swa_sim: waiting for %d agent(s) on domain %d (startup timeout %.0f s)\n", n_,
               participant_->domainId(), options_.startup_timeout_s);
  std::vector<std::string> missing;
  while (!dds::shutdownRequested()) {
    if (olderTwinRuns()) return false;
    missing.clear();
    for (int i = 0; i < n_; ++i) {
      const auto k = static_cast<std::size_t>(i);
      if (imu_[k].matched() < 1) missing.push_back(dds::topics::imu(i) + " (no reader)");
      if (det_[k].matched() < 1) missing.push_back(dds::topics::detections(i) + " (no reader)");
      if (gnss_[k].matched() < 1) missing.push_back(dds::topics::gnss(i) + " (no reader)");
      if (cmd_[k].matched() < 1) missing.push_back(dds::topics::cmdVel(i) + " (no writer)");
    }
    if (truth_.matched() < options_.wait_monitors) missing.push_back(std::string(dds::topics::kTruth) + " (monitor)");
    if (events_.matched() < options_.wait_monitors) missing.push_back(std::string(dds::topics::kEvents) + " (monitor)");
    if (missing.empty()) {
      summary_.discovery_s = secondsSince(t0);
      std::fprintf(stderr, "swa_sim: all %d agent(s) discovered in %.2f s\n", n_, summary_.discovery_s);
      return true;
    }
    if (Clock::now() >= deadline) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  if (dds::shutdownRequested()) return false;
  std::ostringstream list;
  for (std::size_t k = 0; k < missing.size() && k < 12; ++k) list << "\n  " << missing[k];
  if (missing.size() > 12) list << "\n  ... and " << missing.size() - 12 << " more";
  std::fprintf(stderr, "swa_sim: discovery incomplete after %.0f s; unmatched endpoints:%s\n",
               options_.startup_timeout_s, list.str().c_str());
  return false;
}

int SimNode::run() {
  if (!awaitDiscovery()) {
    if (summary_.refused_as_twin) return 1;  // publishes nothing: the running simulator owns the swarm's topics
    if (dds::shutdownRequested()) std::fprintf(stderr, "swa_sim: interrupted before the first step\n");
    publishEvent(record::event_kind::kScenarioEnd, record::kAllUavs, 0.0,
                 dds::shutdownRequested() ? "interrupted before start" : "discovery timeout");
    events_.waitForAcknowledgments(1.0);
    return 1;
  }
  const auto t0 = Clock::now();
  if (scenario_.clock.mode == sim::ClockMode::kLockstep) {
    runLockstep();
  } else {
    runRealtime();
  }
  summary_.completed = world_.finished() && !dds::shutdownRequested();
  summary_.wall_time_s = secondsSince(t0) - summary_.handshake_s;
  finishLatency();
  summary_.steps = world_.step_index();
  summary_.sim_time_s = sim::stampSeconds(world_.time_ns());
  summary_.collisions = world_.collisions();
  for (int i = 0; i < n_; ++i) {
    if (!agentAlive(i)) summary_.dead_at_end.push_back(i);
  }
  if (last_truth_step_ != world_.step_index()) publishTruth();
  publishEvent(record::event_kind::kScenarioEnd, record::kAllUavs, 0.0, summary_.completed ? "completed" : "interrupted");
  // Give late readers of the last samples a moment; events are TRANSIENT_LOCAL anyway.
  events_.waitForAcknowledgments(2.0);
  truth_.waitForAcknowledgments(2.0);
  if (truth_csv_.is_open()) truth_csv_.flush();
  std::fprintf(stderr,
               "swa_sim: %s %s run of %d UAVs: %lld steps, %.1f s sim in %.2f s wall (x%.1f), %d collision(s), "
               "%llu dead / %llu rejoined agent event(s), %llu ignored command(s); loop latency over %llu command(s): "
               "p50 %.0f us, p99 %.0f us, max %.0f us; %llu late (%.2f %%), %llu missing (%.2f %%)\n",
               summary_.completed ? "completed" : "INTERRUPTED", clockModeName(scenario_.clock.mode), n_,
               static_cast<long long>(summary_.steps), summary_.sim_time_s, summary_.wall_time_s,
               summary_.wall_time_s > 0 ? summary_.sim_time_s / summary_.wall_time_s : 0.0, summary_.collisions,
               static_cast<unsigned long long>(summary_.agent_dead_events),
               static_cast<unsigned long long>(summary_.agent_rejoined_events),
               static_cast<unsigned long long>(summary_.ignored_commands),
               static_cast<unsigned long long>(summary_.latency.answered), summary_.latency.p50_us,
               summary_.latency.p99_us, summary_.latency.max_us, static_cast<unsigned long long>(summary_.latency.late),
               100.0 * summary_.latency.lateFraction(), static_cast<unsigned long long>(summary_.latency.missing),
               100.0 * summary_.latency.missingFraction());
  return summary_.completed ? 0 : 1;
}

void SimNode::runLockstep() {
  const double startup_s = std::max(options_.agent_timeout_s, options_.startup_timeout_s);
  while (!dds::shutdownRequested()) {
    publishStepOutputs();
    lockstep_.begin(publishSensors(std::nullopt));
    drainLockstep(Clock::duration::zero());  // answers of dead agents are looked at even if nobody is waited for
    // An agent that never answered may still be matching our writers (discovery is not symmetric): it gets the
    // startup timeout, not the agent timeout, for its first answer.
    const double timeout_s = lockstep_.waitingForNewcomer() ? startup_s : options_.agent_timeout_s;
    auto deadline = std::max(Clock::now(), reconnect_grace_until_) + seconds(timeout_s);
    // Checked at least once per step (stepping and publishing take milliseconds), in the answer wait and in the
    // acknowledgment wait: wherever the simulator is stopped, the stall is seen, and the agents it kept from answering
    // get that much longer (a stall seen here may predate the deadline: then they get more than needed, harmless).
    bool checked = false;
    while (!checked || (!lockstep_.complete() && !dds::shutdownRequested())) {
      checked = true;
      const auto now = Clock::now();
      const Clock::duration lost = stall_.check(now);
      if (lost > Clock::duration::zero()) {
        deadline += lost;  // the agents had no chance to answer while the simulator did not run
        noteStall(lost, now);
        deadline = std::max(deadline, reconnect_grace_until_ + seconds(timeout_s));
      }
      if (lockstep_.complete() || dds::shutdownRequested()) break;
      if (now >= deadline) break;
      drainLockstep(std::min<Clock::duration>(deadline - now, kPollPeriod));
    }
    if (dds::shutdownRequested()) break;
    for (const int i : lockstep_.expire()) {
      ++summary_.agent_dead_events;
      std::fprintf(stderr, "swa_sim: t = %.2f s: agent %d did not answer within %.3f s: dead, UAV %d on failsafe\n",
                   sim::stampSeconds(world_.time_ns()), i, timeout_s, i);
      publishEvent(record::event_kind::kAgentDead, i, timeout_s, "no answer within the agent timeout");
    }
    awaitSensorAcks(deadline);
    if (dds::shutdownRequested()) break;
    if (world_.finished()) break;
    world_.step();
  }
}

void SimNode::awaitSensorAcks(Clock::time_point& deadline) {
  // The agent orders its inputs by stamp (sample_order.h), which reproduces the closed loop only if this step's
  // detections and GNSS fix are in its queue before the next step's IMU sample. DDS orders samples per topic, not
  // across topics (a repaired loss on one topic, or another transport path, lets the next IMU overtake them), so
  // wait until each live agent has acknowledged them: an RTPS acknowledgment follows the reader's listener call.
  // Bounded by the step's deadline, so a stalled agent costs at most one agent timeout per step. Waited in slices of
  // one poll period, so a stall of the simulator here is seen and moves the deadline like in the answer wait.
  const auto acknowledged = [&](dds::Writer<msg::Detections>& det, dds::Writer<msg::GnssFix>& gnss) {
    const auto slice_s = [&] {
      const auto left = std::min<Clock::duration>(deadline - Clock::now(), kPollPeriod);
      return std::max(0.0, std::chrono::duration<double>(left).count());
    };
    while (!dds::shutdownRequested()) {
      if (det.waitForAcknowledgments(slice_s()) && gnss.waitForAcknowledgments(slice_s())) return true;
      const auto now = Clock::now();
      const Clock::duration lost = stall_.check(now);
      if (lost > Clock::duration::zero()) {
        deadline += lost;
        noteStall(lost, now);
      }
      if (now >= deadline) return false;
    }
    return false;
  };
  for (int i = 0; i < n_; ++i) {
    const auto k = static_cast<std::size_t>(i);
    if (!side_written_[k] || !lockstep_.alive(i)) continue;
    if (!acknowledged(det_[k], gnss_[k])) ++summary_.unacknowledged_sensor_steps;
  }
}

void SimNode::drainLockstep(Clock::duration wait) {
  batch_.clear();
  queue_.drain(batch_, wait);
  for (const Answer& a : batch_) {
    if (!fromCommander(a)) continue;
    if (a.setpoint.uav_id() != static_cast<std::uint32_t>(a.uav)) {
      ++summary_.ignored_commands;
      continue;
    }
    recordLatency(a);
    switch (lockstep_.onAnswer(a.uav, a.setpoint.answered_stamp_ns())) {
      case Verdict::kApply:
        apply(a);
        break;
      case Verdict::kRejoin:
        apply(a);
        ++summary_.agent_rejoined_events;
        std::fprintf(stderr, "swa_sim: t = %.2f s: agent %d answers again: rejoined\n",
                     sim::stampSeconds(world_.time_ns()), a.uav);
        publishEvent(record::event_kind::kAgentRejoined, a.uav, 0.0, "answering again");
        break;
      case Verdict::kIgnore:
        ++summary_.ignored_commands;
        break;
    }
  }
}

void SimNode::runRealtime() {
  const double speed = scenario_.clock.speed;
  const agent::StampNs dt_ns = sim::stepPeriodNs(scenario_.dynamics.rate_hz);
  const auto timeout = seconds(options_.agent_timeout_s);

  // Handshake: the clock starts once every agent has closed the loop once. Discovery is not symmetric: when the
  // simulator has matched every agent's endpoints, an agent may not have matched the simulator's yet, and samples
  // written meanwhile reach it (TRANSIENT_LOCAL) only once it has, i.e. late. So step 0's samples are published
  // untimed, and pacing starts when each agent has answered them (typically within a few ms), or after the startup
  // timeout (agents still silent are then declared dead by the agent timeout as usual). Step 0 is not in the latency
  // statistics: its answers measure discovery, not the loop.
  const auto t_handshake = Clock::now();
  time_latency_ = false;
  publishStepOutputs();
  publishSensors(std::nullopt);
  const auto handshake_deadline = t_handshake + seconds(options_.startup_timeout_s);
  const auto everyoneAnswered = [this] {
    return std::all_of(rt_last_applied_.begin(), rt_last_applied_.end(), [](const auto& a) { return a.has_value(); });
  };
  while (!everyoneAnswered() && !dds::shutdownRequested()) {
    const auto now = Clock::now();
    if (now >= handshake_deadline) break;
    drainRealtime(std::min<Clock::duration>(handshake_deadline - now, kPollPeriod));
  }
  time_latency_ = true;
  summary_.handshake_s = secondsSince(t_handshake);
  if (!everyoneAnswered() && !dds::shutdownRequested()) {
    std::fprintf(stderr, "swa_sim: not every agent answered step 0 within %.0f s; starting the clock anyway\n",
                 options_.startup_timeout_s);
  }

  auto start = Clock::now();
  for (auto& t : rt_last_answer_) t = start;
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
    for (auto& t : rt_last_answer_) t = std::max(std::min(t + lost, now), reconnect_grace_until_);
  };
  stall_.restart(Clock::now());
  while (!world_.finished() && !dds::shutdownRequested()) {
    absorbStall(Clock::now());
    auto target = scheduledTime(world_.time_ns() + dt_ns);  // the next step
    do {
      const auto now = Clock::now();
      absorbStall(now);
      target = scheduledTime(world_.time_ns() + dt_ns);
      drainRealtime(now < target ? std::min<Clock::duration>(target - now, kPollPeriod) : Clock::duration::zero());
    } while (Clock::now() < target && !dds::shutdownRequested());
    absorbStall(Clock::now());
    const auto now = Clock::now();
    for (int i = 0; i < n_; ++i) {
      const auto k = static_cast<std::size_t>(i);
      if (rt_alive_[k] && now - rt_last_answer_[k] > timeout) {
        rt_alive_[k] = false;
        ++summary_.agent_dead_events;
        std::fprintf(stderr, "swa_sim: t = %.2f s: no setpoint from agent %d for %.3f s: dead, UAV %d on failsafe\n",
                     sim::stampSeconds(world_.time_ns()), i, options_.agent_timeout_s, i);
        publishEvent(record::event_kind::kAgentDead, i, options_.agent_timeout_s, "no setpoint within the agent timeout");
      }
    }
    if (dds::shutdownRequested()) break;
    world_.step();
    step_lag_.add(wallNs(Clock::now()) - wallNs(target));
    publishStepOutputs();
    // This step's IMU samples are answered late once the next step is due.
    publishSensors(scheduledTime(world_.time_ns() + dt_ns));
  }
  // The last step's samples are judged like every other: collect their answers until they are due.
  if (!dds::shutdownRequested()) collectLateAnswers(scheduledTime(world_.time_ns() + dt_ns));
}

void SimNode::noteStall(Clock::duration lost, Clock::time_point now) {
  ++summary_.stalls;
  const double s = std::chrono::duration<double>(lost).count();
  summary_.stalled_s += s;
  gate_.shift(lost, now);  // no commander could be heard while the simulator did not run
  const bool lease_long = lost >= kLeaseLongStall;
  if (lease_long) reconnect_grace_until_ = now + kReconnectGrace;
  std::fprintf(stderr,
               "swa_sim: t = %.2f s: the simulator itself did not run for %.3f s: its deadlines moved by that much%s "
               "(no agent is blamed for it)\n",
               sim::stampSeconds(world_.time_ns()), s,
               lease_long ? ", and the agents get 4 s more to find it again (the stall outlasted the DDS lease)" : "");
}

void SimNode::drainRealtime(Clock::duration wait) {
  batch_.clear();
  queue_.drain(batch_, wait);
  const agent::StampNs now_ns = world_.time_ns();
  for (const Answer& a : batch_) {
    if (!fromCommander(a)) continue;
    const auto k = static_cast<std::size_t>(a.uav);
    const agent::StampNs answered = a.setpoint.answered_stamp_ns();
    if (a.setpoint.uav_id() == static_cast<std::uint32_t>(a.uav)) recordLatency(a);
    // The latest setpoint wins; answers from the future belong to a previous run (replayed command history).
    const bool newer = !rt_last_applied_[k] || answered > *rt_last_applied_[k];
    if (a.setpoint.uav_id() != static_cast<std::uint32_t>(a.uav) || !newer || answered > now_ns) {
      ++summary_.ignored_commands;
      continue;
    }
    rt_last_applied_[k] = answered;
    rt_last_answer_[k] = Clock::now();
    apply(a);
    if (!rt_alive_[k]) {
      rt_alive_[k] = true;
      ++summary_.agent_rejoined_events;
      std::fprintf(stderr, "swa_sim: t = %.2f s: agent %d answers again: rejoined\n", sim::stampSeconds(now_ns),
                   a.uav);
      publishEvent(record::event_kind::kAgentRejoined, a.uav, 0.0, "answering again");
    }
  }
}

void SimNode::collectLateAnswers(Clock::time_point until) {
  while (!dds::shutdownRequested()) {
    const auto now = Clock::now();
    if (now >= until) break;
    batch_.clear();
    queue_.drain(batch_, std::min<Clock::duration>(until - now, kPollPeriod));
    for (const Answer& a : batch_) {
      if (fromCommander(a) && a.setpoint.uav_id() == static_cast<std::uint32_t>(a.uav)) recordLatency(a);
    }
  }
  // What arrived in time but was not drained yet.
  batch_.clear();
  queue_.drain(batch_, Clock::duration::zero());
  for (const Answer& a : batch_) {
    if (fromCommander(a) && a.setpoint.uav_id() == static_cast<std::uint32_t>(a.uav)) recordLatency(a);
  }
}

void SimNode::recordLatency(const Answer& a) {
  if (!time_latency_) return;
  latency_.answered(a.uav, a.setpoint.answered_seq(), a.setpoint.answered_stamp_ns(), wallNs(a.received));
}

void SimNode::finishLatency() {
  latency_.finish(wallNs(Clock::now()));
  summary_.latency = latency_.report();
  const bool realtime = scenario_.clock.mode == sim::ClockMode::kRealtime;
  summary_.step_lag_p99_us = realtime ? step_lag_.quantileNs(0.99) * 1e-3 : std::nan("");
  summary_.step_lag_max_us = realtime ? step_lag_.maxNs() * 1e-3 : std::nan("");
}

bool SimNode::fromCommander(const Answer& a) {
  const Admission admission = gate_.admit(a.uav, a.writer, a.received);
  if (admission == Admission::kRefused) {
    ++summary_.refused_commands;
    if (gate_.firstRefusal(a.uav, a.writer)) {
      summary_.refused_writers = gate_.refusedWriters();
      std::fprintf(stderr,
                   "swa_sim: t = %.2f s: a second writer on %s (writer %s) while the current one is active: its "
                   "commands are refused (a second agent with this id, or another program writing it)\n",
                   sim::stampSeconds(world_.time_ns()), dds::topics::cmdVel(a.uav).c_str(), guidText(a.writer).c_str());
    }
    return false;
  }
  if (admission == Admission::kHandover && gate_.handovers() != summary_.command_handovers) {
    summary_.command_handovers = gate_.handovers();
    std::fprintf(stderr, "swa_sim: t = %.2f s: %s now written by writer %s (the previous one fell silent)\n",
                 sim::stampSeconds(world_.time_ns()), dds::topics::cmdVel(a.uav).c_str(), guidText(a.writer).c_str());
  }
  return true;
}

bool SimNode::olderTwinRuns() {
  if (!participant_->mustGiveWay()) {
    noteYoungerTwin();
    return false;
  }
  const std::optional<dds::Peer> twin = participant_->twin();
  std::fprintf(stderr,
               "swa_sim: REFUSING to run: another swa_sim (pid %ld on host %s) was already running in %s on domain "
               "%d; two simulators would publish two worlds to the same agents. Stop it, or use another SWA_SWARM.\n",
               twin ? twin->card->pid : 0L, twin ? twin->card->host.c_str() : "?",
               twin && !twin->card->swarm.empty() ? ("swarm " + twin->card->swarm).c_str() : "the default swarm",
               participant_->domainId());
  summary_.refused_as_twin = true;
  return true;
}

void SimNode::noteYoungerTwin() {
  const std::optional<dds::Peer> twin = participant_->twin();
  if (!twin || twin->key == reported_twin_) return;
  reported_twin_ = twin->key;
  std::fprintf(stderr, "swa_sim: a second swa_sim (pid %ld on host %s) joined this swarm; it started later and must "
                       "refuse to run\n",
               twin->card->pid, twin->card->host.c_str());
}

void SimNode::apply(const Answer& a) {
  world_.command(a.uav, wire::fromMsg(a.setpoint));
  ++summary_.applied_commands;
}

bool SimNode::agentAlive(int uav) const {
  return scenario_.clock.mode == sim::ClockMode::kLockstep ? lockstep_.alive(uav)
                                                             : rt_alive_[static_cast<std::size_t>(uav)];
}

void SimNode::publishStepOutputs() {
  if (world_.step_index() % 10 == 0) noteYoungerTwin();
  for (const sim::Event& e : world_.events()) publishEvent(record::eventOf(e));
  if (world_.step_index() % options_.truth_every == 0 || world_.finished()) publishTruth();
  const wire::ClockTick tick{static_cast<std::uint64_t>(world_.step_index()), world_.time_ns(),
                             sim::stepPeriodNs(scenario_.dynamics.rate_hz)};
  msg::Clock m = wire::toMsg(tick, ++clock_seq_);
  if (!clock_.write(m)) ++summary_.write_failures;
}

std::vector<std::optional<agent::StampNs>> SimNode::publishSensors(std::optional<Clock::time_point> due) {
  const std::optional<WallNs> due_ns = due ? std::optional<WallNs>(wallNs(*due)) : std::nullopt;
  std::vector<std::optional<agent::StampNs>> imu_stamps(static_cast<std::size_t>(n_));
  const std::vector<sim::UavSensors>& sensors = world_.sensors();
  for (int i = 0; i < n_; ++i) {
    const auto k = static_cast<std::size_t>(i);
    const auto id = static_cast<std::uint32_t>(i);
    const sim::UavSensors& s = sensors[k];
    side_written_[k] = s.detections.has_value() || s.gnss.has_value();
    // The closed loop's equal-stamp order (IMU, detections, GNSS); the agent restores it whatever the arrival order.
    if (s.imu) {
      msg::Imu m = wire::toMsg(*s.imu, id, ++imu_seq_[k]);
      const WallNs published_ns = wallNs(Clock::now());
      if (imu_[k].write(m)) {
        if (time_latency_) latency_.published(i, imu_seq_[k], s.imu->stamp_ns, published_ns, due_ns);
        imu_stamps[k] = s.imu->stamp_ns;
      } else {
        ++summary_.write_failures;
      }
    }
    if (s.detections) {
      msg::Detections m = wire::toMsg(*s.detections, id, ++det_seq_[k]);
      if (!det_[k].write(m)) ++summary_.write_failures;
    }
    if (s.gnss) {
      msg::GnssFix m = wire::toMsg(*s.gnss, id, ++gnss_seq_[k]);
      if (!gnss_[k].write(m)) ++summary_.write_failures;
    }
  }
  return imu_stamps;
}

void SimNode::publishTruth() {
  last_truth_step_ = world_.step_index();
  wire::SwarmTruth truth{world_.time_ns(), world_.truth(), {}};
  for (const sim::UavTruth& t : truth.uavs) {
    truth.agent_alive.push_back(agentAlive(t.id));
    if (truth_csv_.is_open()) {
      truth_csv_ << world_.step_index() << ',' << world_.time_ns() << ',' << t.id << ',' << t.position_m.x() << ','
                 << t.position_m.y() << ',' << t.velocity_mps.x() << ',' << t.velocity_mps.y() << ','
                 << t.acceleration_mps2.x() << ',' << t.acceleration_mps2.y() << ',' << t.heading_rad << ','
                 << (agentAlive(t.id) ? 1 : 0) << ',' << (t.gnss_valid ? 1 : 0) << ',' << (t.failsafe ? 1 : 0)
                 << '\n';
    }
  }
  msg::SwarmTruth m = wire::toMsg(truth, ++truth_seq_);
  if (!truth_.write(m)) ++summary_.write_failures;
}

void SimNode::publishEvent(const char* kind, int uav, double value, const std::string& text) {
  publishEvent({static_cast<double>(world_.time_ns()) * 1e-9, kind, uav, -1, value, text});
}

void SimNode::publishEvent(const record::EventRecord& event) {
  msg::ScenarioEvent m = wire::toMsg(event, ++event_seq_);
  if (!events_.write(m)) ++summary_.write_failures;
}

std::string SimNode::summaryJson() const {
  const LatencyReport& l = summary_.latency;
  // Members in this order; NaN (a statistic of an empty set) is written as null.
  const nlohmann::ordered_json j{
      {"completed", summary_.completed},
      {"clock_mode", clockModeName(scenario_.clock.mode)},
      {"uav_count", n_},
      {"seed", scenario_.seed},
      {"steps", summary_.steps},
      {"sim_time_s", summary_.sim_time_s},
      {"wall_time_s", summary_.wall_time_s},
      {"discovery_s", summary_.discovery_s},
      {"handshake_s", summary_.handshake_s},
      {"collisions", summary_.collisions},
      {"applied_commands", summary_.applied_commands},
      {"ignored_commands", summary_.ignored_commands},
      {"refused_commands", summary_.refused_commands},
      {"refused_writers", summary_.refused_writers},
      {"command_handovers", summary_.command_handovers},
      {"unacknowledged_sensor_steps", summary_.unacknowledged_sensor_steps},
      {"agent_dead_events", summary_.agent_dead_events},
      {"agent_rejoined_events", summary_.agent_rejoined_events},
      {"stalls", summary_.stalls},
      {"stalled_s", summary_.stalled_s},
      {"dead_at_end", summary_.dead_at_end},
      {"write_failures", summary_.write_failures},
      {"latency_commands_judged", l.published},
      {"latency_commands_answered", l.answered},
      {"latency_p50_us", l.p50_us},
      {"latency_p99_us", l.p99_us},
      {"latency_max_us", l.max_us},
      {"latency_mean_us", l.mean_us},
      {"latency_quantile_resolution", LogHistogram::relativeResolution()},
      {"late_commands", l.late},
      {"late_fraction", l.lateFraction()},
      {"missing_answers", l.missing},
      {"missing_fraction", l.missingFraction()},
      {"duplicate_answers", l.duplicates},
      {"unmatched_answers", l.unmatched},
      {"step_lag_p99_us", summary_.step_lag_p99_us},
      {"step_lag_max_us", summary_.step_lag_max_us},
  };
  return j.dump(2) + "\n";
}

}  // namespace swa::sim_node

// AgentNode's samples from the listeners to the core: foreign detection sets converted, the stamp orderer, and per
// IMU sample the command written and the 10 Hz state made due. Apart from run()'s loop, which only watches the
// connection and the clock: this is what every sample costs.

#include "agent_node.h"

#include <chrono>
#include <cstdio>
#include <type_traits>
#include <utility>

#include "swa/app/cpu_time.h"
#include "swa/wire/ros_types.h"
#include "swa/wire/samples.h"

namespace swa::agent_node {
namespace {

constexpr agent::StampNs kStatePeriodNs = 100'000'000;  // 10 Hz

}  // namespace

void AgentNode::onForeign(const agent::ForeignDetectionSet& set) {
  std::optional<agent::DetectionSet> converted;
  std::uint32_t seq = 0;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    converted = adapter_.convert(set);
    seq = ++foreign_seq_;
  }
  // Dropped sets are counted in the adapter (logged at exit); the rest is SWA's own detections from here on.
  if (converted) onInput(Input(wire::toMsg(*converted, static_cast<std::uint32_t>(id_), seq)));
}

void AgentNode::onInput(Input&& in) {
  // Stamp read before the sample is moved into the orderer.
  const auto [stream, stamp] = std::visit(
      [](const auto& m) {
        using M = std::decay_t<decltype(m)>;
        const Stream st = std::is_same_v<M, msg::Imu>          ? Stream::kImu
                          : std::is_same_v<M, msg::Detections> ? Stream::kDetections
                                                               : Stream::kGnss;
        return std::make_pair(st, m.header().stamp_ns());
      },
      in);
  const std::lock_guard<std::mutex> lock(mutex_);
  if (!replay_.pass(stream, stamp)) {
    stats_.replayed = replay_.dropped();
    return;
  }
  last_input_ = std::chrono::steady_clock::now();
  if (stream == Stream::kImu) last_imu_at_ = last_input_;
  if (stream == Stream::kDetections) last_detections_at_ = last_input_;
  const auto* det = std::get_if<msg::Detections>(&in);
  if (det != nullptr && det->items().size() > agent_.config().limits.max_detections) {
    handle(in);  // rejected whole by the core (and counted) before it is stored anywhere
    return;
  }
  order_.push(stream, stamp, std::move(in));
  while (auto entry = order_.pop()) handle(entry->payload);
  stats_.forced_releases = order_.forcedReleases();
}

void AgentNode::onFrame(msg::SensorFrame&& frame) {
  // In the order the simulator's separate topics were written in lockstep; the orderer processes the IMU sample
  // first whatever the order (sample_order.h).
  for (msg::Detections& d : frame.detection_set()) onInput(Input(std::move(d)));
  for (msg::GnssFix& g : frame.gnss_fix()) onInput(Input(std::move(g)));
  for (msg::Imu& i : frame.imu_sample()) onInput(Input(std::move(i)));
}

void AgentNode::handle(Input& in) {
  const auto foreign = [&](std::uint32_t named) {
    if (feed_.isFor(named)) return false;
    if (stats_.foreign++ == 0) {
      std::fprintf(stderr, "swa_agent %d: dropping a sample addressed to UAV %u (further ones counted silently)\n", id_,
                   named);
    }
    return true;
  };

  if (const auto* imu = std::get_if<msg::Imu>(&in)) {
    if (foreign(imu->uav_id())) return;
    if (stats_.imu++ == 0) {
      // The CPU time so far: what the samples cost is the CPU time at the end minus this (bench_scale).
      std::fprintf(stderr,
                   "swa_agent %d: first IMU sample (stamp %lld ns, cmd readers %d) %.3f s after start, %.3f s of CPU "
                   "time before it\n",
                   id_, static_cast<long long>(imu->header().stamp_ns()), cmd_writer_.matched(),
                   std::chrono::duration<double>(std::chrono::steady_clock::now() - started_).count(),
                   app::processCpuTime().total_s());
    }
    const agent::StampNs stamp = imu->header().stamp_ns();
    if (pending_state_ns_ && stamp > *pending_state_ns_) {
      publishState(*pending_state_ns_);
      pending_state_ns_.reset();
    }
    const std::uint64_t resyncs = agent_.diagnostics().stamp_resyncs;
    const std::uint64_t fallbacks = agent_.diagnostics().tilt_fallbacks;
    const std::optional<msg::VelocitySetpoint> answer = feed_.onImu(*imu);
    last_imu_stamp_ = stamp;
    reportMission();
    if (fallbacks == 0 && agent_.diagnostics().tilt_fallbacks > 0) {
      std::fprintf(stderr,
                   "swa_agent %d: an IMU sample without the accelerometer focal.imu_source asks for (stamp %lld ns): "
                   "read from the tilt, which takes drag and wind for acceleration; further ones counted (a bridge "
                   "that reads no accelerometer, e.g. PX4 without sensor_combined on its topic list, sends none)\n",
                   id_, static_cast<long long>(stamp));
    }
    if (agent_.diagnostics().stamp_resyncs != resyncs) {
      std::fprintf(stderr,
                   "swa_agent %d: the IMU clock restarted (now at stamp %lld ns): estimates restarted on the new "
                   "timeline\n",
                   id_, static_cast<long long>(stamp));
    }
    // A rejected sample (counted in the state's reject counters) is not answered: a flood of bad samples must not
    // turn into a flood of commands. A UAV whose valid samples stop gets no commands, and its autopilot's own
    // offboard timeout takes over (the simulator's failsafe: hover after failsafe_timeout_s).
    if (!answer) return;
    had_fresh_imu_ = true;
    last_fresh_imu_ = std::chrono::steady_clock::now();
    msg::VelocitySetpoint out = *answer;
    if (cmd_writer_.write(out)) {
      ++stats_.commands;
    } else {
      ++stats_.write_failures;
    }
    if (twist_writer_) {
      geometry_msgs::msg::TwistStamped twist = wire::toTwistStamped(out);
      if (!twist_writer_.write(twist)) ++stats_.write_failures;
    }
    last_cmd_ = out;
    if (!state_due_set_ || stamp >= next_state_ns_) {
      pending_state_ns_ = stamp;
      // Next 100 ms boundary after this stamp (floor division, also for negative stamps).
      agent::StampNs floor = stamp / kStatePeriodNs;
      if (stamp % kStatePeriodNs < 0) --floor;
      next_state_ns_ = (floor + 1) * kStatePeriodNs;
      state_due_set_ = true;
    }
  } else if (const auto* det = std::get_if<msg::Detections>(&in)) {
    if (foreign(det->observer_id())) return;
    ++stats_.detections;
    feed_.onDetections(*det);
  } else if (const auto* gnss = std::get_if<msg::GnssFix>(&in)) {
    if (foreign(gnss->uav_id())) return;
    ++stats_.gnss;
    feed_.onGnss(*gnss);
  }
}

}  // namespace swa::agent_node

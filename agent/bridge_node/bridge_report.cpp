// What swa_px4_bridge says when it stops: the final counts and latencies in the log, and the --summary-out JSON
// (bench_px4_bridge.sh reads it). Apart from bridge_node.cpp, whose listeners and loop serve the vehicle while it
// flies: this runs once, after the participant is closed.

#include "bridge_node.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <optional>
#include <string>

#include "swa/app/log_histogram.h"
#include "swa/app/signals.h"
#include "swa/px4/gnss.h"

namespace swa::bridge_node {

void BridgeNode::logFinalCounts() const {
  const autopilot::BridgeCounters& c = core_.counters();
  std::fprintf(
      stderr,
      "swa_px4_bridge %d: stopping on signal %d after %llu attitude samples (%llu rejected, %llu out of "
      "order), %llu commands (%llu applied, %llu replayed, %llu not newer, %llu for unknown samples, %llu "
      "non-finite, %llu clamped, %llu from another writer); sent %llu setpoints (and %llu answers again to a "
      "repeated sample), %llu heartbeats, %llu requests\n",
      id_, app::shutdownSignal(), static_cast<unsigned long long>(c.attitude_in),
      static_cast<unsigned long long>(c.attitude_rejected), static_cast<unsigned long long>(c.attitude_out_of_order),
      static_cast<unsigned long long>(c.commands_in), static_cast<unsigned long long>(c.commands_applied),
      static_cast<unsigned long long>(c.commands_replayed), static_cast<unsigned long long>(c.commands_not_newer),
      static_cast<unsigned long long>(c.commands_unknown_sample), static_cast<unsigned long long>(c.commands_nonfinite),
      static_cast<unsigned long long>(c.commands_clamped), static_cast<unsigned long long>(gate_.refused()),
      static_cast<unsigned long long>(c.setpoints_out), static_cast<unsigned long long>(answers_repeated_),
      static_cast<unsigned long long>(c.heartbeats_out), static_cast<unsigned long long>(c.requests_out));
  if (const std::optional<px4::GnssForwardCounters> g = vehicle_->gnssCounters()) logGnssCounts(*g);
  const auto us = [](const app::LogHistogram& h, double q) { return h.quantileNs(q) * 1e-3; };
  std::fprintf(stderr,
               "swa_px4_bridge %d: latency over %llu answered samples, p50 / p99: attitude in -> setpoint out %.0f / "
               "%.0f us; of which the agent (imu out -> cmd_vel in) %.0f / %.0f us, the bridge %.0f / %.0f us\n",
               id_, static_cast<unsigned long long>(hop_.count()), us(hop_, 0.5), us(hop_, 0.99), us(agent_loop_, 0.5),
               us(agent_loop_, 0.99), us(bridge_part_, 0.5), us(bridge_part_, 0.99));
}

void BridgeNode::logGnssCounts(const px4::GnssForwardCounters& g) const {
  const auto n = [](std::uint64_t v) { return static_cast<unsigned long long>(v); };
  std::fprintf(stderr,
               "swa_px4_bridge %d: GNSS from %s: %llu position reports (%llu out of order), %llu fixes; forwarded %llu "
               "valid, %llu not valid (no fix %llu, not xy_valid %llu, dead reckoning %llu, bad numbers %llu, stale "
               "fix %llu, no usable reference %llu); %llu clock restarts, %llu origin changes\n",
               id_, core_.autopilot().name, n(g.positions_in), n(g.out_of_order), n(g.gps_in), n(g.forwarded),
               n(g.invalid_forwarded), n(g.no_fix), n(g.not_xy_valid), n(g.dead_reckoning), n(g.bad_numbers),
               n(g.stale_gps), n(g.unusable_reference), n(g.clock_restarts), n(g.origin_changes));
}

void BridgeNode::writeSummary() const {
  if (options_.summary_out.empty()) return;
  const autopilot::BridgeCounters& c = core_.counters();
  const auto us = [](const app::LogHistogram& h, double q) {
    const double v = h.quantileNs(q) * 1e-3;
    return std::isfinite(v) ? std::to_string(v) : std::string("null");
  };
  std::ofstream out(options_.summary_out);
  out << "{\n  \"uav\": " << id_ << ",\n  \"attitude_in\": " << c.attitude_in
      << ",\n  \"commands_applied\": " << c.commands_applied << ",\n  \"setpoints_out\": " << c.setpoints_out
      << ",\n  \"heartbeats_out\": " << c.heartbeats_out << ",\n  \"answered_samples\": " << hop_.count()
      << ",\n  \"hop_p50_us\": " << us(hop_, 0.5) << ",\n  \"hop_p99_us\": " << us(hop_, 0.99)
      << ",\n  \"agent_loop_p50_us\": " << us(agent_loop_, 0.5)
      << ",\n  \"agent_loop_p99_us\": " << us(agent_loop_, 0.99)
      << ",\n  \"bridge_part_p50_us\": " << us(bridge_part_, 0.5)
      << ",\n  \"bridge_part_p99_us\": " << us(bridge_part_, 0.99);
  // GNSS forwarded from the vehicle only (PX4 without --no-gnss): a count of nothing would claim a fact.
  if (const std::optional<px4::GnssForwardCounters> g = vehicle_->gnssCounters()) {
    out << ",\n  \"gnss_forwarded\": " << g->forwarded << ",\n  \"gnss_invalid_forwarded\": " << g->invalid_forwarded
        << ",\n  \"origin_changes\": " << g->origin_changes << ",\n  \"unusable_reference\": " << g->unusable_reference;
  }
  out << "\n}\n";
  if (!out.flush()) {
    std::fprintf(stderr, "swa_px4_bridge %d: cannot write --summary-out %s\n", id_, options_.summary_out.c_str());
  }
}

}  // namespace swa::bridge_node

#pragma once
// Puts the samples of the agent's three input topics back into one deterministic order before they reach the agent
// core. DDS orders samples within a topic, not across topics: IMU, detections and GNSS of one simulator step can
// arrive in any interleaving. The in-process closed loop (sim/batch/closed_loop.cpp) feeds them by stamp, and at
// equal stamps IMU first, then detections, then GNSS; this class reproduces that order from any arrival order.
//
// Rule: entries leave in (stamp, stream, arrival) order. An IMU sample leaves at once. A detection set or GNSS fix
// with stamp s waits until an IMU sample with stamp >= s has arrived (so the IMU of the same step, which the command
// answers, is processed first), or, if the IMU stream has gone quiet, until a later detection / GNSS sample is more
// than `hold_limit_ns` newer (so a sensor setup without IMU still gets its detections, late but in order).
// Pure: no clock, no DDS, no threads; the node's worker owns one instance.

#include <algorithm>
#include <cstdint>
#include <optional>
#include <tuple>
#include <utility>
#include <vector>

#include "swa/agent/samples.h"

namespace swa::agent_node {

enum class Stream : int { kImu = 0, kDetections = 1, kGnss = 2 };

template <class Payload>
class StampOrderer {
 public:
  struct Entry {
    agent::StampNs stamp_ns = 0;
    Stream stream = Stream::kImu;
    std::uint64_t arrival = 0;
    Payload payload;
  };

  explicit StampOrderer(agent::StampNs hold_limit_ns) : hold_limit_ns_(hold_limit_ns) {}

  void push(Stream stream, agent::StampNs stamp_ns, Payload payload) {
    if (stream == Stream::kImu) {
      imu_watermark_ns_ = have_imu_ ? std::max(imu_watermark_ns_, stamp_ns) : stamp_ns;
      have_imu_ = true;
    } else {
      newest_other_ns_ = have_other_ ? std::max(newest_other_ns_, stamp_ns) : stamp_ns;
      have_other_ = true;
    }
    heap_.push_back(Entry{stamp_ns, stream, next_arrival_++, std::move(payload)});
    std::push_heap(heap_.begin(), heap_.end(), Later{});
  }

  // The next entry that may be processed now, or nullopt if none may (yet).
  std::optional<Entry> pop() {
    if (heap_.empty() || !releasable(heap_.front())) return std::nullopt;
    std::pop_heap(heap_.begin(), heap_.end(), Later{});
    Entry e = std::move(heap_.back());
    heap_.pop_back();
    return e;
  }

  std::size_t size() const { return heap_.size(); }

 private:
  struct Later {
    bool operator()(const Entry& a, const Entry& b) const {
      return std::make_tuple(a.stamp_ns, static_cast<int>(a.stream), a.arrival) >
             std::make_tuple(b.stamp_ns, static_cast<int>(b.stream), b.arrival);
    }
  };

  bool releasable(const Entry& e) const {
    if (e.stream == Stream::kImu) return true;
    if (have_imu_ && e.stamp_ns <= imu_watermark_ns_) return true;
    if (!have_other_) return false;
    agent::StampNs newer_by = 0;  // corrupt stamps far apart: overflow means "much newer"
    if (__builtin_sub_overflow(newest_other_ns_, e.stamp_ns, &newer_by)) return true;
    return newer_by > hold_limit_ns_;
  }

  agent::StampNs hold_limit_ns_;
  std::vector<Entry> heap_;
  std::uint64_t next_arrival_ = 0;
  bool have_imu_ = false;
  agent::StampNs imu_watermark_ns_ = 0;
  bool have_other_ = false;
  agent::StampNs newest_other_ns_ = 0;
};

}  // namespace swa::agent_node

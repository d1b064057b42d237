#pragma once
// Puts the samples of the agent's three input topics back into one deterministic order before they reach the agent
// core. DDS orders samples within a topic, not across topics: IMU, detections and GNSS of one simulator step can
// arrive in any interleaving. The in-process closed loop (deploy/programs/batch/closed_loop.cpp) feeds them by stamp,
// and at equal stamps IMU first, then detections, then GNSS; this class reproduces that order from any arrival order.
//
// Rule: entries leave in (stamp, stream, arrival) order. An IMU sample leaves at once. A detection set or GNSS fix
// with stamp s waits until an IMU sample with stamp >= s has arrived (so the IMU of the same step, which the command
// answers, is processed first), or, if the IMU stream has gone quiet, until a later detection / GNSS sample is more
// than `hold_limit_ns` newer (so a sensor setup without IMU still gets its detections, late but in order).
//
// Bounded whatever the input: a detection / GNSS sample stamped more than `hold_limit_ns` ahead of the newest IMU
// stamp is not held at all (it leaves at once, and the agent core judges its stamp), and beyond `max_held` entries
// the first one in order leaves at once whatever its stamp. Both count in forcedReleases(); neither happens with a
// sane producer.
// Pure: no clock, no DDS, no threads; the node owns one instance.

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

  static constexpr std::size_t kDefaultMaxHeld = 256;  // 2.5 s of one UAV's three streams at 100 + 10 + 10 Hz

  explicit StampOrderer(agent::StampNs hold_limit_ns, std::size_t max_held = kDefaultMaxHeld)
      : hold_limit_ns_(hold_limit_ns), max_held_(std::max<std::size_t>(max_held, 1)) {}

  void push(Stream stream, agent::StampNs stamp_ns, Payload payload) {
    Entry entry{stamp_ns, stream, next_arrival_++, std::move(payload)};
    if (stream != Stream::kImu && farAhead(entry)) {
      // Not held and not counted as the stream's newest: it would keep every later sample waiting for nothing.
      bypass_.push_back(std::move(entry));
      ++forced_releases_;
      return;
    }
    if (stream == Stream::kImu) {
      imu_watermark_ns_ = have_imu_ ? std::max(imu_watermark_ns_, stamp_ns) : stamp_ns;
      have_imu_ = true;
    } else {
      newest_other_ns_ = have_other_ ? std::max(newest_other_ns_, stamp_ns) : stamp_ns;
      have_other_ = true;
    }
    heap_.push_back(std::move(entry));
    std::push_heap(heap_.begin(), heap_.end(), Later{});
  }

  // The next entry that may be processed now, or nullopt if none may (yet).
  std::optional<Entry> pop() {
    if (!bypass_.empty()) {
      Entry e = std::move(bypass_.back());
      bypass_.pop_back();
      return e;
    }
    if (heap_.empty()) return std::nullopt;
    if (!releasable(heap_.front())) {
      if (heap_.size() <= max_held_) return std::nullopt;
      ++forced_releases_;
    }
    std::pop_heap(heap_.begin(), heap_.end(), Later{});
    Entry e = std::move(heap_.back());
    heap_.pop_back();
    return e;
  }

  std::size_t size() const { return heap_.size() + bypass_.size(); }
  std::uint64_t forcedReleases() const { return forced_releases_; }

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

  // Ahead of the newest IMU stamp by more than the hold limit: no IMU sample will release it in time.
  bool farAhead(const Entry& e) const {
    if (!have_imu_) return false;
    agent::StampNs ahead = 0;
    if (__builtin_sub_overflow(e.stamp_ns, imu_watermark_ns_, &ahead)) return e.stamp_ns > imu_watermark_ns_;
    return ahead > hold_limit_ns_;
  }

  agent::StampNs hold_limit_ns_;
  std::size_t max_held_;
  std::uint64_t forced_releases_ = 0;
  std::vector<Entry> heap_;
  std::vector<Entry> bypass_;  // at most one entry between a push and the pops that follow it
  std::uint64_t next_arrival_ = 0;
  bool have_imu_ = false;
  agent::StampNs imu_watermark_ns_ = 0;
  bool have_other_ = false;
  agent::StampNs newest_other_ns_ = 0;
};

}  // namespace swa::agent_node

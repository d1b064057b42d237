#pragma once
// The hand-off between DDS listener threads and a node's single worker thread. Listeners only push (no processing
// on a middleware thread); the worker drains everything that arrived and processes it in its own order. Unbounded on
// purpose: what bounds memory is the DDS history depth upstream and the worker keeping up, and dropping here would
// silently break lockstep determinism.

#include <chrono>
#include <condition_variable>
#include <deque>
#include <mutex>
#include <utility>
#include <vector>

namespace swa::dds {

template <class T>
class SampleQueue {
 public:
  void push(T value) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      items_.push_back(std::move(value));
    }
    cv_.notify_one();
  }

  // Moves everything queued into `out` (appended, arrival order). Waits up to `timeout` for the first item;
  // returns false when nothing arrived in time (or on wake()).
  template <class Rep, class Period>
  bool drain(std::vector<T>& out, std::chrono::duration<Rep, Period> timeout) {
    std::unique_lock<std::mutex> lock(mutex_);
    if (items_.empty() && !woken_) cv_.wait_for(lock, timeout, [this] { return !items_.empty() || woken_; });
    woken_ = false;
    if (items_.empty()) return false;
    for (T& item : items_) out.push_back(std::move(item));
    items_.clear();
    return true;
  }

  // Ends a pending drain() early (e.g. on shutdown); consumed by that drain().
  void wake() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      woken_ = true;
    }
    cv_.notify_all();
  }

  std::size_t size() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return items_.size();
  }

 private:
  mutable std::mutex mutex_;
  std::condition_variable cv_;
  std::deque<T> items_;
  bool woken_ = false;
};

}  // namespace swa::dds

#pragma once
// A deadline on a call that may never return: unless the Deadline is destroyed within `limit`, `on_expiry` runs on a
// thread of its own. Participant's destructor puts one on deleting the participant: Fast DDS 2.9.1 can deadlock
// inside a secured participant (three of its threads waiting on each other; participant_shutdown.cpp), and deleting
// that participant then never returns. Nothing in the process can mend it, so the process exits and its supervisor
// restarts it.
//
//   {
//     const Deadline d(std::chrono::seconds(12), [] { std::_Exit(70); });
//     mayHangForever();
//   }  // returned in time: on_expiry never runs

#include <chrono>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <thread>
#include <utility>

namespace swa::dds {

class Deadline {
 public:
  template <class Rep, class Period>
  Deadline(std::chrono::duration<Rep, Period> limit, std::function<void()> on_expiry)
      : thread_([this, limit, expiry = std::move(on_expiry)] {
          std::unique_lock<std::mutex> lock(mutex_);
          if (!met_changed_.wait_for(lock, limit, [this] { return met_; })) expiry();
        }) {}
  // The call returned: `on_expiry` does not run, unless it already has.
  ~Deadline() {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      met_ = true;
    }
    met_changed_.notify_one();
    thread_.join();
  }
  Deadline(const Deadline&) = delete;
  Deadline& operator=(const Deadline&) = delete;

 private:
  std::mutex mutex_;
  std::condition_variable met_changed_;
  bool met_ = false;
  std::thread thread_;  // last: it starts once the members it uses exist
};

}  // namespace swa::dds

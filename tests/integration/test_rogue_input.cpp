// Issue #11, fault campaign `fuzz`: a rogue DDS publisher (security off, a private domain) drives one swa_agent with
// an adversarial plan, and the agent stays alive, bounded and honest: memory bounded, every command finite and within
// the limit, no command for a rejected sample, its state published throughout (STAGE_NO_INPUT when no valid IMU
// arrives) with the right counters, and normal commands again at once after the rogue stops.

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include <swa/msg/AgentStatePubSubTypes.h>
#include <swa/msg/DetectionsPubSubTypes.h>
#include <swa/msg/GnssFixPubSubTypes.h>
#include <swa/msg/ImuPubSubTypes.h>
#include <swa/msg/VelocitySetpointPubSubTypes.h>

#include "resting_imu.h"
#include "rogue_agent_test.h"
#include "swa/dds/qos_profiles.h"
#include "swa/dds/sample_queue.h"

namespace swa::testing {
namespace {

constexpr int kUav = 1;
constexpr agent::StampNs kMs = 1'000'000;
constexpr agent::StampNs kSec = 1'000'000'000;
constexpr double kNan = std::numeric_limits<double>::quiet_NaN();

// Resident set size of a process, from /proc (kB); 0 if it is gone.
long rssKb(pid_t pid) {
  std::ifstream status("/proc/" + std::to_string(pid) + "/status");
  std::string key;
  while (status >> key) {
    if (key == "VmRSS:") {
      long kb = 0;
      status >> kb;
      return kb;
    }
    status.ignore(std::numeric_limits<std::streamsize>::max(), '\n');
  }
  return 0;
}

class RogueInput : public RogueAgentTest {
 protected:
  void SetUp() override {
    startAgentAndRogue("swa_rogue", /*dir_per_test=*/false, 37, kUav);
    det_ = rogue_->writer<msg::DetectionsPubSubType>(dds::topics::detections(kUav), dds::qos::kDetectionsGnssWriter);
    gnss_ = rogue_->writer<msg::GnssFixPubSubType>(dds::topics::gnss(kUav), dds::qos::kDetectionsGnssWriter);
    rogue_->reader<msg::AgentStatePubSubType>(dds::topics::state(kUav), dds::qos::kStateReader, states_.listener());
  }

  bool waitMatched(double bound_s) {
    return waitFor([this] { return imu_.matched() > 0 && det_.matched() > 0 && gnss_.matched() > 0; }, bound_s);
  }

  void poll() {
    cmds_.take();
    states_.take();
  }

  // A genuine-looking step: IMU level, every 10th step detections of three neighbours on a ring around the UAV.
  void genuineStep(agent::StampNs t, std::uint32_t& seq) {
    msg::Imu m = restingImu(kUav, t, ++seq);
    imu_.write(m);
    if ((t / (10 * kMs)) % 10 == 0) {
      msg::Detections d;
      d.header().stamp_ns(t);
      d.header().seq(seq);
      d.observer_id(kUav);
      for (int j = 0; j < 3; ++j) {
        msg::Detection x;
        x.target_id(ringNeighbourId(j));
        x.x_m(ringNeighbour(j).x());
        x.y_m(ringNeighbour(j).y());
        d.items().push_back(x);
      }
      det_.write(d);
    }
  }

  // `seconds` of genuine steps at 100 Hz, paced by the wall clock, from sim time `t0`.
  agent::StampNs genuine(agent::StampNs t0, double seconds, std::uint32_t& seq) {
    const int steps = static_cast<int>(seconds * 100);
    const auto start = SteadyClock::now();
    for (int i = 0; i < steps; ++i) {
      genuineStep(t0 + i * 10 * kMs, seq);
      std::this_thread::sleep_until(start + std::chrono::milliseconds(10 * (i + 1)));
    }
    return t0 + steps * 10 * kMs;
  }

  // Commands answering IMU stamps in [from, to).
  int commandsAnswering(agent::StampNs from, agent::StampNs to) const {
    return static_cast<int>(std::count_if(cmds_.seen.begin(), cmds_.seen.end(), [&](const msg::VelocitySetpoint& c) {
      return c.answered_stamp_ns() >= from && c.answered_stamp_ns() < to;
    }));
  }

  Received<msg::AgentState> states_;
  dds::Writer<msg::Detections> det_;
  dds::Writer<msg::GnssFix> gnss_;
};

TEST_F(RogueInput, AgentStaysAliveBoundedAndHonestUnderAnAdversarialPlan) {
  ASSERT_TRUE(waitMatched(20.0)) << "agent's readers never matched\n" << readFile(dir_ / "agent.log");
  std::uint32_t seq = 0;
  // GIVEN 2 s of genuine samples from t = 5 s
  agent::StampNs t = genuine(5 * kSec, 2.0, seq);
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  poll();
  const agent::StampNs genuine_end = t;
  const int answered_genuine = commandsAnswering(5 * kSec, genuine_end);
  ASSERT_GT(answered_genuine, 150) << readFile(dir_ / "agent.log");
  const long rss_before = rssKb(agent_->pid());
  ASSERT_GT(rss_before, 0);

  // WHEN the rogue sends three times 2000 detection sets of 1000 entries stamped an hour and INT64_MAX ahead (before
  // issue #11: held forever by the stamp orderer, +43 MB/s). Each set is acknowledged by the agent's reader before the
  // next is written: every one of them reaches the agent, however busy the host (written as fast as the writer could,
  // a busy host's agent received 2952 of 6000 before its reader history overflowed), so each must be counted.
  // A genuine IMU sample (and no detections, which would move the detection stream's clock past the sets below)
  // every 100 sets: an agent whose IMU falls silent for 6 s while its writer stays matched re-creates its participant
  // (silence_watch.h), and the sets sent meanwhile are lost to it (sanitizer CI: the attack took over 6 s under ASan,
  // 5379 of 6000 counted).
  const auto oversizeAttack = [&] {
    for (int i = 0; i < 2000; ++i) {
      if (i % 100 == 0) {
        t += 10 * kMs;
        msg::Imu m = restingImu(kUav, t, ++seq);
        imu_.write(m);
      }
      msg::Detections d;
      d.header().stamp_ns(i % 2 == 0 ? t + 3600 * kSec : std::numeric_limits<agent::StampNs>::max());
      d.observer_id(kUav);
      d.items().resize(1000);
      det_.write(d);
      det_.waitForAcknowledgments(10.0);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
  };
  oversizeAttack();
  const long rss_first = rssKb(agent_->pid());
  oversizeAttack();
  const long rss_second = rssKb(agent_->pid());
  oversizeAttack();
  const long rss_third = rssKb(agent_->pid());
  // ... sets of 30 (not oversize) with NaN positions, ids of 1e6, far-future stamps
  for (int i = 0; i < 200; ++i) {
    msg::Detections d;
    d.header().stamp_ns(t - 5 * kMs + i * 10'000);  // after the last genuine set, each 10 us later
    d.observer_id(kUav);
    d.items().resize(30);
    for (auto& x : d.items()) {
      x.target_id(i % 2 == 0 ? 1'000'000 : 3);
      x.x_m(i % 3 == 0 ? kNan : 1e300);
    }
    det_.write(d);
  }
  // ... IMU samples with NaN, 1e300 heading, one 60 s ahead, one at INT64_MAX, and GNSS garbage
  for (int i = 0; i < 50; ++i) {
    msg::Imu m = restingImu(kUav, i == 0   ? t + 60 * kSec
                                  : i == 1 ? std::numeric_limits<agent::StampNs>::max()
                                           : t + i * kMs);
    if (i >= 2) {
      m.roll_rad(i % 2 == 0 ? kNan : 0.0);
      m.heading_rad(i % 2 == 0 ? 0.0 : 1e300);
    }
    imu_.write(m);
    msg::GnssFix g;
    g.uav_id(kUav);
    g.header().stamp_ns(t + i * kMs);
    g.valid(true);
    g.x_m(kNan);
    g.std_m(-1.0);
    gnss_.write(g);
  }
  // (everything so far delivered before the flood: a KEEP_LAST writer history may drop unacknowledged samples)
  imu_.waitForAcknowledgments(5.0);
  det_.waitForAcknowledgments(5.0);
  gnss_.waitForAcknowledgments(5.0);
  // ... and a flood of 20000 stale IMU samples (random old stamps) as fast as it can
  std::mt19937_64 rng(7);
  std::uniform_int_distribution<agent::StampNs> stale(-10 * kSec, -kMs);  // old: before every genuine stamp
  const auto flood_start = SteadyClock::now();
  for (int i = 0; i < 20000; ++i) {
    msg::Imu m = restingImu(kUav, stale(rng));
    imu_.write(m);
  }
  const double flood_s = std::chrono::duration<double>(SteadyClock::now() - flood_start).count();
  // THEN the genuine stream goes on at once: its next 2 s are answered (before: hover for 60 s after the +60 s
  // sample), with no command for any stale sample
  const agent::StampNs resume = t;
  t = genuine(t, 2.0, seq);
  // ... a producer restart: the clock starts again at 0 and is followed within a few samples
  const agent::StampNs restart_end = genuine(0, 2.0, seq);
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  poll();
  const long rss_after = rssKb(agent_->pid());
  ASSERT_FALSE(agent_->wait(0.0).has_value()) << "agent died\n" << readFile(dir_ / "agent.log");
  std::printf(
      "flood of 20000 stale samples written in %.2f s; agent RSS %ld kB before the rogue, %ld kB after the "
      "first 2000 oversize sets, %ld kB after the second, %ld kB after the third, %ld kB at the end\n",
      flood_s, rss_before, rss_first, rss_second, rss_third, rss_after);
  EXPECT_GE(commandsAnswering(resume, t), 195);
  EXPECT_EQ(commandsAnswering(-10 * kSec, 0), 0) << "commands answered stale samples";
  EXPECT_GE(commandsAnswering(5 * kSec, genuine_end), answered_genuine);
  // (the restarted producer's first resync_samples - 1 = 3 samples are rejected, the rest answered)
  EXPECT_GE(commandsAnswering(0, restart_end), 195);
  // AND memory is bounded: 6000 sets of 1000 detections are ~290 MB, which the stamp orderer held before issue #11.
  // Now the agent holds none of them; what grows is the middleware's sample pool, up to its QoS bound (the
  // detections reader keeps at most 100 samples, idl/runtime/dds/profiles.xml: 100 x ~48 kB serialised = ~5 MB)
#ifdef __SANITIZE_ADDRESS__
  // (AddressSanitizer keeps up to 256 MB of freed memory in quarantine, which the first two batches fill: in the
  // sanitizer build the bound is on what the third batch adds, ~80 MB if the sets were held; LeakSanitizer checks at
  // exit what was never freed)
  EXPECT_LT(rss_third - rss_second, 16 * 1024);
#else
  EXPECT_LT(rss_after - rss_before, 16 * 1024);
#endif
  // AND every command was finite and within the 2 m/s limit, its yaw rate finite and within the default
  // control.max_yaw_rate_radps (0.5; this all-round agent holds its heading: 0), whatever heading the rogue sent
  for (const msg::VelocitySetpoint& c : cmds_.seen) {
    ASSERT_TRUE(std::isfinite(c.vx_mps()) && std::isfinite(c.vy_mps()));
    ASSERT_LE(std::hypot(c.vx_mps(), c.vy_mps()), 2.0);
    ASSERT_TRUE(std::isfinite(c.yaw_rate_radps()));
    ASSERT_LE(std::abs(c.yaw_rate_radps()), 0.5);
  }
  // AND the latest state counts what the rogue did
  ASSERT_FALSE(states_.seen.empty());
  const msg::AgentState& s = states_.seen.back();
  EXPECT_EQ(s.rejected_oversize(), 6000u);  // every one written, each acknowledged before the next
  EXPECT_GE(s.rejected_future_stamp(), 2u);
  EXPECT_GE(s.rejected_nonfinite(), 1u);
  EXPECT_GE(s.rejected_bad_id(), 1u);
  EXPECT_GE(s.rejected_implausible(), 1u);
  EXPECT_GE(s.rejected_out_of_order(), 1000u);  // DDS itself may drop part of a flood (KEEP_LAST history)
  EXPECT_EQ(s.stamp_resyncs(), 1u);

  // WHEN the rogue falls silent
  const std::size_t states_before = states_.seen.size();
  std::this_thread::sleep_for(std::chrono::milliseconds(3200));
  poll();
  // THEN the agent still publishes its state, every second, and says it has no input
  ASSERT_GE(states_.seen.size(), states_before + 2) << "the state went silent";
  EXPECT_EQ(states_.seen.back().stage(), msg::STAGE_NO_INPUT);
  EXPECT_FALSE(agent_->wait(0.0).has_value());
  // AND it stops cleanly when asked (in the sanitizer build, LeakSanitizer's verdict on the agent is this status)
  EXPECT_EQ(agent_->stop(10.0), 0) << readFile(dir_ / "agent.log");
}

}  // namespace
}  // namespace swa::testing

// Fuzz at the Agent facade: seeded streams of every kind of sample with every kind of garbage, in every mode; the
// command is always finite and within saturation and the reject counters account for exactly the bad inputs. Also:
// stamps more than INT64_MAX ns apart re-synchronise without overflow. Shared helpers: agent_input_support.h.

#include <climits>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "agent_input_support.h"
#include "swa/agent/agent.h"
#include "swa/agent/stream_clock.h"

namespace swa::agent {
namespace {

using namespace testing;  // agent_input_support.h

// ===============================================================================================================
// Fuzz: every kind of sample with every kind of garbage, in every mode.

class Fuzzer {
 public:
  Fuzzer(std::uint64_t seed, const LimitsConfig& limits) : rng_(seed), limits_(limits) {}

  double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng_); }
  bool chance(double p) { return uniform(0.0, 1.0) < p; }
  int integer(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng_); }
  template <typename T, std::size_t N>
  T pick(const T (&values)[N]) {
    return values[static_cast<std::size_t>(integer(0, static_cast<int>(N) - 1))];
  }

  // Stamps: one clock shared by the three streams advances 0.3-7 ms per input (so IMU, detections and GNSS stay
  // roughly in step and the agent really tracks), and very rarely jumps up to an hour ahead. A sample normally
  // carries the clock; sometimes its stream's previous stamp again, sometimes a stamp up to 2 s before it.
  StampNs stamp(int stream) {
    clock_ += static_cast<StampNs>(uniform(3e5, 7e6));
    if (chance(5e-4)) clock_ += static_cast<StampNs>(uniform(1e9, 3.6e12));
    const double r = uniform(0.0, 1.0);
    if (r < 0.04) return last_[stream];
    if (r < 0.08) return last_[stream] - static_cast<StampNs>(uniform(1.0, 2e9));
    last_[stream] = clock_;
    return clock_;
  }

  // A double that is usually in [lo, hi] and otherwise garbage.
  double value(double lo, double hi, double p_garbage) {
    if (!chance(p_garbage)) return uniform(lo, hi);
    static const double garbage[] = {kNan,
                                     -kNan,
                                     kInf,
                                     -kInf,
                                     1e300,
                                     -1e300,
                                     std::numeric_limits<double>::max(),
                                     std::numeric_limits<double>::denorm_min(),
                                     -0.0,
                                     1e-300};
    return pick(garbage);
  }

  int id(bool& bad) {
    const double r = uniform(0.0, 1.0);
    bad = false;
    if (r < 0.25) return kAnonymousId;
    if (r < 0.90) return integer(0, 30);
    static const int ids[] = {-2, -1000, INT_MIN, 1'000'001, INT_MAX, kFirstAnonymousTrackId, 0, 1'000'000};
    const int v = pick(ids);
    bad = v != kAnonymousId && (v < 0 || v > limits_.max_target_id);
    return v;
  }

  std::mt19937_64 rng_;
  LimitsConfig limits_;
  StampNs clock_ = kT0;
  StampNs last_[3] = {kT0, kT0, kT0};
};

// What the spec says must happen to one input: how many rejections it causes for sure, and how many more it may
// cause (inputs whose classification the spec leaves open).
struct Verdict {
  std::uint64_t bad = 0;
  std::uint64_t maybe = 0;
};

// The stamp rules of the spec: each stream's own clock (stream_clock.h, tested on its own in test_stream_clock.cpp),
// detections and GNSS within the window of the IMU's clock, and a restart of the IMU's clock restarting the others.
// A detection or GNSS stamp too far ahead of its own stream but within the IMU's window resumes that stream (it was
// silent, as ArduPilot's GNSS is while its receiver is unhealthy).
struct FuzzOracle {
  explicit FuzzOracle(const LimitsConfig& lim)
      : window(static_cast<StampNs>(lim.max_stamp_jump_s * 1e9)),
        resync(lim.resync_samples),
        clock{fresh(), fresh(), fresh()} {}

  StreamClock fresh() const { return StreamClock(window, resync); }

  enum class Stamp { kOk, kOutOfOrder, kFuture };
  Stamp judge(int stream, StampNs st) {
    const StreamClock::Verdict v = clock[stream].check(st);
    if (v == StreamClock::Verdict::kOutOfOrder) return Stamp::kOutOfOrder;
    StampNs to_imu = 0;
    const bool near_imu = stream != 0 && clock[0].started() && !__builtin_sub_overflow(st, clock[0].last(), &to_imu) &&
                          to_imu <= window && to_imu >= -window;
    if (v == StreamClock::Verdict::kFuture && near_imu) clock[stream].resume(st);
    if (v == StreamClock::Verdict::kFuture && !near_imu) return Stamp::kFuture;
    if (v == StreamClock::Verdict::kResync && stream == 0) {
      clock[1] = fresh();
      clock[2] = fresh();
    }
    if (stream == 0 || !clock[0].started()) return Stamp::kOk;
    StampNs offset = 0;
    if (__builtin_sub_overflow(st, clock[0].last(), &offset) || offset > window) return Stamp::kFuture;
    return offset < -window ? Stamp::kOutOfOrder : Stamp::kOk;
  }

  StampNs window;
  int resync;
  StreamClock clock[3];
  bool have_heading = false;
};

// Counts a stamp verdict into `res`; true when the stamp is accepted.
template <class Result>
bool countStamp(FuzzOracle::Stamp v, Result& res) {
  if (v == FuzzOracle::Stamp::kOk) return true;
  ++res.bad;
  if (v == FuzzOracle::Stamp::kFuture) {
    ++res.generated.future;
  } else {
    ++res.generated.out_of_order;
  }
  return false;
}

// Everything a fuzz run observed; filled without gtest macros so the run can also execute in a forked child.
struct FuzzResult {
  std::uint64_t inputs = 0;
  std::uint64_t clean_inputs = 0;     // inputs with nothing to reject
  std::uint64_t moving_commands = 0;  // commands with |v| > 0.1 m/s: the agent was really steering
  std::uint64_t bad = 0;              // inputs the spec certainly rejects
  std::uint64_t maybe = 0;            // inputs the spec leaves open (absurd but SPD detection covariance)
  RejectCounters generated;           // certainly-bad inputs by the category the generator gave them
  RejectCounters rejected;            // the agent's counters at the end
  int bad_commands = 0;               // non-finite or above v_max + 1e-12
  int nonfinite_diagnostics = 0;
  int nonfinite_tracks = 0;
  int wrong_bookkeeping = 0;  // seq / answered stamp / commands counter
  int miscounted = 0;         // inputs after which the counters did not move by the expected amount
  std::vector<std::string> first_failures;
};

FuzzResult runFuzz(Mode mode, std::uint64_t seed, int samples) {
  AgentConfig config = configFor(mode);
  config.sensor.fov_deg = 240.0;  // so every command also carries a heading-control yaw rate (issue #26)
  Agent agent(config);
  Fuzzer fz(seed, config.limits);
  FuzzOracle oracle(config.limits);
  const LimitsConfig& lim = config.limits;
  const double v_max = config.control.v_max_mps;

  FuzzResult res;
  std::uint64_t imu_count = 0, last_seq = 0;
  std::uint64_t bad_before = 0, maybe_before = 0, rejected_before = 0;
  auto report = [&res](int& count, const std::string& message) {
    ++count;
    if (res.first_failures.size() < 8) res.first_failures.push_back(message);
  };

  for (int n = 0; n < samples; ++n) {
    ++res.inputs;
    // The first three inputs are detection sets, so detections before any IMU occur for sure.
    const double kind = n < 3 ? 0.7 : fz.uniform(0.0, 1.0);
    std::string what;
    if (kind < 0.6) {
      ImuSample s;
      s.stamp_ns = fz.stamp(0);
      s.roll_rad = fz.value(-0.85, 0.85, 0.05);
      s.pitch_rad = fz.value(-0.85, 0.85, 0.05);
      s.heading_rad = fz.value(-4.0, 4.0, 0.05);
      // Mostly with an accelerometer (message set 5), sometimes without: what a tilt-only bridge sends.
      if (fz.chance(0.95)) {
        AccelerometerSample a;
        a.roll_rad = fz.value(-0.85, 0.85, 0.02);
        a.pitch_rad = fz.value(-0.85, 0.85, 0.02);
        a.specific_force_body_mps2 =
            Vec3(fz.value(-20.0, 20.0, 0.02), fz.value(-20.0, 20.0, 0.02), fz.value(-200.0, 200.0, 0.02));
        s.accelerometer = a;
      }
      const AccelerometerSample* a = s.accelerometer ? &*s.accelerometer : nullptr;
      const bool finite = std::isfinite(s.roll_rad) && std::isfinite(s.pitch_rad) && std::isfinite(s.heading_rad) &&
                          (a == nullptr || (a->specific_force_body_mps2.allFinite() && std::isfinite(a->roll_rad) &&
                                            std::isfinite(a->pitch_rad)));
      const bool tilt_ok = std::abs(s.roll_rad) <= lim.max_tilt_rad && std::abs(s.pitch_rad) <= lim.max_tilt_rad &&
                           std::abs(s.heading_rad) <= lim.max_abs_heading_rad;
      // An agent fusing the accelerometer takes one level enough and within a MEMS part's range (none: the tilt).
      const bool accel_ok = config.focal.imu_source != ImuSource::kAccelerometer || a == nullptr ||
                            (std::abs(a->roll_rad) <= lim.max_tilt_rad && std::abs(a->pitch_rad) <= lim.max_tilt_rad &&
                             a->specific_force_body_mps2.norm() <= kMaxSpecificForce_mps2);
      if (!finite) {
        ++res.bad, ++res.generated.nonfinite;
      } else if (!tilt_ok || !accel_ok) {
        ++res.bad, ++res.generated.implausible;
      } else if (countStamp(oracle.judge(0, s.stamp_ns), res)) {
        oracle.have_heading = true;
      }
      what = "IMU stamp " + std::to_string(s.stamp_ns) + " roll " + std::to_string(s.roll_rad) + " pitch " +
             std::to_string(s.pitch_rad) + " heading " + std::to_string(s.heading_rad) +
             (a ? " accelerometer |f| " + std::to_string(a->specific_force_body_mps2.norm()) : " no accelerometer");
      const VelocityCommand c = agent.onImu(s);
      ++imu_count;
      if (!c.velocity_mps.allFinite() || !(c.velocity_mps.norm() <= v_max + 1e-12)) {
        report(res.bad_commands, "input " + std::to_string(n) + ": command (" + std::to_string(c.velocity_mps.x()) +
                                     ", " + std::to_string(c.velocity_mps.y()) + ") not finite or above v_max");
      }
      if (!std::isfinite(c.yaw_rate_radps) || !(std::abs(c.yaw_rate_radps) <= config.control.max_yaw_rate_radps)) {
        report(res.bad_commands, "input " + std::to_string(n) + ": yaw rate " + std::to_string(c.yaw_rate_radps) +
                                     " not finite or above its limit");
      }
      if (c.seq != last_seq + 1 || c.answered_stamp_ns != s.stamp_ns) {
        report(res.wrong_bookkeeping, "input " + std::to_string(n) + ": seq / answered stamp wrong");
      }
      last_seq = c.seq;
      if (c.velocity_mps.norm() > 0.1) ++res.moving_commands;
    } else if (kind < 0.85) {
      DetectionSet set;
      set.stamp_ns = fz.stamp(1);
      const double r = fz.uniform(0.0, 1.0);
      const std::size_t size = r < 0.03   ? lim.max_detections + 1 + static_cast<std::size_t>(fz.integer(0, 20))
                               : r < 0.05 ? lim.max_detections
                                          : static_cast<std::size_t>(fz.integer(0, 12));
      Verdict per_detection;
      std::uint64_t per_detection_bad_id = 0;
      for (std::size_t i = 0; i < size; ++i) {
        Detection d;
        bool bad_id = false;
        d.target_id = fz.id(bad_id);
        bool bad_value = false, maybe_value = false;
        d.position_body_m = Vec2(fz.uniform(-45.0, 45.0), fz.uniform(-45.0, 45.0));
        if (fz.chance(0.06)) {
          static const Vec2 garbage[] = {Vec2(kNan, 0.0),
                                         Vec2(0.0, kInf),
                                         Vec2(-kInf, kNan),
                                         Vec2(1e300, 0.0),
                                         Vec2(0.0, -1e300),
                                         Vec2(1e6 + 1.0, 0.0),
                                         Vec2(std::numeric_limits<double>::max(), 1.0)};
          d.position_body_m = fz.pick(garbage);
          bad_value = true;
        }
        const double c = fz.uniform(0.0, 1.0);
        if (c < 0.5) {
          // no covariance: configured R_o
        } else if (c < 0.85) {
          Mat2 L;
          L << fz.uniform(0.01, 1.0), 0.0, fz.uniform(-0.5, 0.5), fz.uniform(0.01, 1.0);
          d.covariance_m2 = Mat2(L * L.transpose());
        } else {
          static const Mat2 bad_cov[] = {mat(kNan, 0.0, 0.0, 0.1), mat(0.1, kInf, kInf, 0.1),
                                         mat(-0.1, 0.0, 0.0, 0.1), mat(0.1, 0.05, -0.05, 0.1),
                                         mat(0.1, 0.5, 0.5, 0.1),  Mat2::Zero()};
          static const Mat2 odd_cov[] = {Mat2::Identity() * 1e300, Mat2::Identity() * 1e-100, mat(1e-6, 0.0, 0.0, 1e6)};
          if (fz.chance(0.6)) {
            d.covariance_m2 = fz.pick(bad_cov);
            bad_value = true;
          } else {
            // Symmetric positive definite but possibly absurd (1e300 m^2): the spec does not say whether that is
            // implausible, so it may or may not be counted.
            d.covariance_m2 = fz.pick(odd_cov);
            maybe_value = (*d.covariance_m2)(0, 0) > 1e200;
          }
        }
        if (bad_id || bad_value) {
          ++per_detection.bad;
          if (bad_id) ++per_detection_bad_id;
        } else if (maybe_value) {
          ++per_detection.maybe;
        }
        set.detections.push_back(d);
      }
      if (size > lim.max_detections) {
        ++res.bad, ++res.generated.oversize;
      } else if (!oracle.have_heading) {
        ++res.bad, ++res.generated.no_heading;
      } else if (!countStamp(oracle.judge(1, set.stamp_ns), res)) {
      } else {
        res.bad += per_detection.bad;
        res.maybe += per_detection.maybe;
        res.generated.bad_id += per_detection_bad_id;
      }
      what = "detection set of " + std::to_string(size) + " stamp " + std::to_string(set.stamp_ns);
      agent.onDetections(set);
    } else {
      GnssSample g;
      g.stamp_ns = fz.stamp(2);
      g.valid = fz.chance(0.8);
      g.position_m = Vec2(fz.value(-50.0, 50.0, 0.05), fz.value(-50.0, 50.0, 0.05));
      g.std_m = fz.value(0.01, 5.0, 0.05);
      if (fz.chance(0.02)) g.std_m = fz.chance(0.5) ? 0.0 : -fz.uniform(0.0, 10.0);
      if (fz.chance(0.01)) g.position_m.x() = lim.max_abs_position_m + 1.0;
      const bool finite = g.position_m.allFinite() && std::isfinite(g.std_m);
      // A std whose square overflows (>= 1e150 here: 1e300, DBL_MAX) is no receiver's claim: implausible like
      // std <= 0 (see AbsurdStdDoesNotPoisonTheAbsoluteEstimator).
      const bool plausible = g.std_m > 0.0 && g.std_m < 1e150 && g.position_m.norm() <= lim.max_abs_position_m;
      if (g.valid && !finite) {
        ++res.bad, ++res.generated.nonfinite;
      } else if (g.valid && !plausible) {
        ++res.bad, ++res.generated.implausible;
      } else {
        countStamp(oracle.judge(2, g.stamp_ns), res);
      }
      std::ostringstream os;
      os << "GNSS valid " << g.valid << " stamp " << g.stamp_ns << " position " << g.position_m.transpose() << " std "
         << g.std_m;
      what = os.str();
      agent.onGnss(g);
    }

    const Diagnostics& d = agent.diagnostics();
    // Each input moves the counters by exactly the number of rejections the spec demands of it.
    const std::uint64_t delta = d.rejected.total() - rejected_before;
    if (delta < res.bad - bad_before || delta > res.bad - bad_before + res.maybe - maybe_before) {
      report(res.miscounted,
             "input " + std::to_string(n) + " (" + what + "): counters moved by " + std::to_string(delta) +
                 ", expected " + std::to_string(res.bad - bad_before) +
                 (res.maybe > maybe_before ? " (+ up to " + std::to_string(res.maybe - maybe_before) + ")" : ""));
    }
    if (res.bad == bad_before && res.maybe == maybe_before) ++res.clean_inputs;
    rejected_before = d.rejected.total();
    bad_before = res.bad;
    maybe_before = res.maybe;
    if (!finiteDiagnostics(d)) {
      report(res.nonfinite_diagnostics, "input " + std::to_string(n) + ": non-finite diagnostics estimate, position (" +
                                            std::to_string(d.position_m.x()) + ", " + std::to_string(d.position_m.y()) +
                                            ") P00 " + std::to_string(d.position_cov_m2(0, 0)));
    }
    if (!finiteTracks(agent.bank())) report(res.nonfinite_tracks, "input " + std::to_string(n) + ": non-finite track");
    if (d.commands != imu_count) report(res.wrong_bookkeeping, "commands counter != IMU samples");
  }
  res.rejected = agent.diagnostics().rejected;
  return res;
}

// A clean run of one stream takes about 0.6 s optimised and a few seconds in the sanitizer build.
constexpr unsigned kDeadlineS = 60;

TEST(AgentInputFuzz, CommandsFiniteAndSaturatedAndCountersMatchInEveryMode) {
  for (const Mode mode : {Mode::kSwa, Mode::kStandalone, Mode::kAnchored}) {
    for (const std::uint64_t seed : {11u, 12u}) {
      SCOPED_TRACE("mode " + toString(mode) + " seed " + std::to_string(seed));
      // 3 modes x 2 seeds x 170 000 = 1.02e6 inputs per run of this test (issue #11: at least 1e6 per CI run, which
      // the Release suite makes). The sanitizer build, 30 times slower here, takes a tenth: every kind of input still
      // comes thousands of times.
#ifdef SWA_SANITIZED
      constexpr int kSamples = 17'000;
#else
      constexpr int kSamples = 170'000;
#endif
      // GIVEN a seeded stream of 1.7e5 random IMU, detection and GNSS samples mixing valid values, NaN, +-inf, 1e300,
      // DBL_MAX, huge and negative IDs, repeated / backward / far-jumping stamps (which re-synchronise the streams
      // after a few consistent samples) and oversized sets
      // WHEN an agent consumes it (first in a child process: an agent that hangs must fail, not stall the suite)
      const std::string hang = runWithDeadline(kDeadlineS, [&] { runFuzz(mode, seed, kSamples); });
      EXPECT_EQ(hang, "") << "agent did not get through the fuzz stream";
      if (!hang.empty()) continue;
      const FuzzResult r = runFuzz(mode, seed, kSamples);

      // THEN every command (velocity and yaw rate) is finite and within saturation, the estimate and the tracks stay
      // finite
      EXPECT_EQ(r.bad_commands, 0) << "commands not finite or above v_max";
      EXPECT_EQ(r.nonfinite_diagnostics, 0) << "inputs after which the diagnostics estimate was not finite";
      EXPECT_EQ(r.nonfinite_tracks, 0) << "inputs after which a track estimate was not finite";
      EXPECT_EQ(r.wrong_bookkeeping, 0);
      EXPECT_EQ(r.miscounted, 0) << "inputs after which the counters did not move as the spec demands";
      for (const std::string& f : r.first_failures) ADD_FAILURE() << f;

      // AND the counters account for exactly the bad inputs (each rejected input counts once)
      EXPECT_GE(r.rejected.total(), r.bad) << "fewer rejections than certainly-bad inputs";
      EXPECT_LE(r.rejected.total(), r.bad + r.maybe) << "more rejections than bad inputs";
      // AND every category was generated and counted
      for (auto field : {&RejectCounters::nonfinite, &RejectCounters::out_of_order, &RejectCounters::oversize,
                         &RejectCounters::bad_id, &RejectCounters::implausible, &RejectCounters::no_heading,
                         &RejectCounters::future}) {
        EXPECT_GT(r.generated.*field, 0u);
        EXPECT_GT(r.rejected.*field, 0u);
      }
      EXPECT_GE(r.rejected.no_heading, 3u);
      // Sanity of the stream: most inputs are entirely good, so the agent really runs (tracks, frames, commands).
      EXPECT_GT(r.clean_inputs, r.inputs / 2);
      EXPECT_GT(r.moving_commands, 100u);
    }
  }
}

// ===============================================================================================================
// Stamps far apart

// A producer whose clock jumps from near INT64_MIN to near INT64_MAX (a restart, or garbage): the jump is a future
// stamp, a consistent new timeline re-synchronises after limits.resync_samples samples, and nothing on the way
// overflows (secondsBetween of stamps more than INT64_MAX ns apart saturates; UBSan would abort on a wrap).
TEST(AgentInputStamps, StampsMoreThanInt64MaxApartResynchroniseWithoutOverflow) {
  for (const Mode mode : {Mode::kSwa, Mode::kStandalone, Mode::kAnchored}) {
    SCOPED_TRACE("mode " + toString(mode));
    const StampNs lo = std::numeric_limits<StampNs>::min();
    const StampNs hi = std::numeric_limits<StampNs>::max();
    // GIVEN an agent whose first samples are stamped near INT64_MIN, with a tentative track of neighbour 1
    Agent agent(configFor(mode));
    ImuSample imu;
    imu.stamp_ns = lo;
    agent.onImu(imu);
    DetectionSet set;
    set.stamp_ns = lo + 1;
    set.detections = {det(1, 5.0, 0.0)};
    agent.onDetections(set);
    GnssSample g;
    g.valid = true;
    g.stamp_ns = lo + 2;
    agent.onGnss(g);
    ASSERT_NE(agent.bank().find(1), nullptr);
    // WHEN the IMU goes on near INT64_MAX, 10 ms apart
    const int k = agent.config().limits.resync_samples;
    std::vector<VelocityCommand> commands;
    for (int i = k - 1; i >= 0; --i) {
      imu.stamp_ns = hi - i * 10'000'000;
      commands.push_back(agent.onImu(imu));
    }
    // THEN the first k - 1 are future stamps (answered with the previous command, not fresh), the k-th
    // re-synchronises the IMU clock and restarts the estimates: neighbour 1's track is gone
    RejectCounters want;
    want.future = static_cast<std::uint64_t>(k - 1);
    expectCounters(agent.diagnostics().rejected, want);
    EXPECT_EQ(agent.diagnostics().stamp_resyncs, 1u);
    for (int i = 0; i < k - 1; ++i) EXPECT_FALSE(commands[static_cast<std::size_t>(i)].fresh);
    EXPECT_TRUE(commands.back().fresh);
    EXPECT_EQ(agent.bank().find(1), nullptr);
    // AND detections and GNSS on the new timeline are accepted at once, old-timeline ones are out of order
    set.stamp_ns = hi - 5;
    set.detections = {det(2, 0.0, 5.0)};
    agent.onDetections(set);
    g.stamp_ns = hi - 3;
    agent.onGnss(g);
    set.stamp_ns = lo + 10;
    agent.onDetections(set);
    want.out_of_order = 1;
    expectCounters(agent.diagnostics().rejected, want);
    EXPECT_NE(agent.bank().find(2), nullptr);
    for (const VelocityCommand& v : commands) {
      EXPECT_TRUE(allFinite(v.velocity_mps));
      EXPECT_LE(v.velocity_mps.norm(), agent.config().control.v_max_mps);
    }
    EXPECT_TRUE(finiteDiagnostics(agent.diagnostics()));
  }
}

}  // namespace
}  // namespace swa::agent

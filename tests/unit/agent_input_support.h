#pragma once
// Shared support for the agent bad-input tests (test_agent_input_*.cpp, test_agent_behaviour_guards.cpp): bitwise
// comparison helpers, reject-counter checks, agent state comparison, realistic sample streams, the `Twins` fixture
// (a reference agent and a device under test warmed up on the same stream), builders (a heading for an agent,
// detections, detection sets, GNSS fixes), finiteness checks and a fork-based deadline runner.
//
// Each rejection test runs two agents on the same realistic stream: `ref` never sees the bad input, `dut` does.
// The test then asserts that exactly one counter moved, by the exact amount, and that the rest of the agent (track
// bank, both focal filters, diagnostics and every later command) is bit-identical to `ref`.

#include <algorithm>
#include <cmath>
#include <csignal>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <optional>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include "swa/agent/agent.h"

namespace swa::agent::testing {

inline constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
inline constexpr double kInf = std::numeric_limits<double>::infinity();
inline constexpr StampNs kMs = 1'000'000;
inline constexpr StampNs kSec = 1'000'000'000;
inline constexpr StampNs kT0 = 5 * kSec;  // streams start here

// ---------------------------------------------------------------------------------------------------------------
// Bitwise comparison helpers: "no effect" and "deterministic" mean the same bits (-0.0 != 0.0), not NEAR.

inline bool sameBits(double a, double b) {
  std::uint64_t x = 0, y = 0;
  std::memcpy(&x, &a, sizeof x);
  std::memcpy(&y, &b, sizeof y);
  return x == y;
}

template <typename A, typename B>
bool sameBits(const Eigen::MatrixBase<A>& a, const Eigen::MatrixBase<B>& b) {
  if (a.rows() != b.rows() || a.cols() != b.cols()) return false;
  for (Eigen::Index i = 0; i < a.rows(); ++i)
    for (Eigen::Index j = 0; j < a.cols(); ++j)
      if (!sameBits(a(i, j), b(i, j))) return false;
  return true;
}

template <typename A>
bool allFinite(const Eigen::MatrixBase<A>& a) {
  return a.allFinite();
}

inline bool sameCommand(const VelocityCommand& a, const VelocityCommand& b) {
  return a.stamp_ns == b.stamp_ns && a.answered_stamp_ns == b.answered_stamp_ns && a.seq == b.seq &&
         sameBits(a.velocity_mps, b.velocity_mps);
}

// ---------------------------------------------------------------------------------------------------------------
// Counters.

inline RejectCounters only(std::uint64_t RejectCounters::*field, std::uint64_t n) {
  RejectCounters c;
  c.*field = n;
  return c;
}

inline void expectCounters(const RejectCounters& got, const RejectCounters& want) {
  EXPECT_EQ(got.nonfinite, want.nonfinite) << "rejected.nonfinite";
  EXPECT_EQ(got.out_of_order, want.out_of_order) << "rejected.out_of_order";
  EXPECT_EQ(got.oversize, want.oversize) << "rejected.oversize";
  EXPECT_EQ(got.bad_id, want.bad_id) << "rejected.bad_id";
  EXPECT_EQ(got.implausible, want.implausible) << "rejected.implausible";
  EXPECT_EQ(got.no_heading, want.no_heading) << "rejected.no_heading";
  EXPECT_EQ(got.future, want.future) << "rejected.future";
}

// ---------------------------------------------------------------------------------------------------------------
// State comparison: everything observable about an agent except the reject counters (and, when an IMU sample was
// rejected, the command count that every answered IMU sample increments).

inline void expectSameFilter(const FocalEstimator& a, const FocalEstimator& b, const char* what) {
  EXPECT_EQ(a.initialized(), b.initialized()) << what;
  EXPECT_EQ(a.time(), b.time()) << what;
  EXPECT_TRUE(sameBits(a.state().x, b.state().x)) << what << " x differs:\n" << a.state().x << "\nvs\n" << b.state().x;
  EXPECT_TRUE(sameBits(a.state().P, b.state().P)) << what << " P differs";
}

inline void expectSameTracks(const TrackBank& a, const TrackBank& b) {
  ASSERT_EQ(a.tracks().size(), b.tracks().size());
  for (std::size_t i = 0; i < a.tracks().size(); ++i) {
    const Track& s = a.tracks()[i];
    const Track& t = b.tracks()[i];
    SCOPED_TRACE("track index " + std::to_string(i) + " id " + std::to_string(s.id));
    EXPECT_EQ(s.id, t.id);
    EXPECT_EQ(s.anonymous, t.anonymous);
    EXPECT_EQ(s.confirmed, t.confirmed);
    EXPECT_EQ(s.hits, t.hits);
    EXPECT_EQ(s.created_ns, t.created_ns);
    EXPECT_EQ(s.last_detection_ns, t.last_detection_ns);
    EXPECT_EQ(s.time_ns, t.time_ns);
    EXPECT_TRUE(sameBits(s.estimate.x, t.estimate.x));
    EXPECT_TRUE(sameBits(s.estimate.P, t.estimate.P));
  }
}

inline void expectSameDiagnostics(const Diagnostics& a, const Diagnostics& b, bool with_counters, bool with_commands) {
  EXPECT_EQ(a.stamp_ns, b.stamp_ns);
  EXPECT_EQ(a.mode, b.mode);
  EXPECT_EQ(a.stage, b.stage);
  EXPECT_TRUE(sameBits(a.position_m, b.position_m)) << a.position_m.transpose() << " vs " << b.position_m.transpose();
  EXPECT_TRUE(sameBits(a.velocity_mps, b.velocity_mps));
  EXPECT_TRUE(sameBits(a.position_cov_m2, b.position_cov_m2));
  EXPECT_TRUE(sameBits(a.velocity_cov_m2ps2, b.velocity_cov_m2ps2));
  EXPECT_EQ(a.frame_valid, b.frame_valid);
  EXPECT_TRUE(sameBits(a.frame_centre_m, b.frame_centre_m));
  EXPECT_EQ(a.fit_case, b.fit_case);
  EXPECT_EQ(a.neighbour_count, b.neighbour_count);
  EXPECT_EQ(a.neighbour_ids, b.neighbour_ids);
  EXPECT_EQ(a.confirmed_tracks, b.confirmed_tracks);
  EXPECT_EQ(a.tentative_tracks, b.tentative_tracks);
  if (with_counters) expectCounters(a.rejected, b.rejected);
  if (with_commands) {
    EXPECT_EQ(a.commands, b.commands);
  }
  EXPECT_EQ(a.frame_shifts, b.frame_shifts);
  EXPECT_EQ(a.frame_resets, b.frame_resets);
  EXPECT_EQ(a.gnss_valid, b.gnss_valid);
}

inline void expectSameState(const Agent& a, const Agent& b, bool with_counters, bool with_commands) {
  expectSameTracks(a.bank(), b.bank());
  expectSameFilter(a.focal(), b.focal(), "focal");
  expectSameFilter(a.absolute(), b.absolute(), "absolute");
  expectSameDiagnostics(a.diagnostics(), b.diagnostics(), with_counters, with_commands);
}

// ---------------------------------------------------------------------------------------------------------------
// Sample streams.

struct Event {
  enum class Kind { kImu, kDetections, kGnss };
  Kind kind = Kind::kImu;
  ImuSample imu;
  DetectionSet detections;
  GnssSample gnss;
};

inline std::optional<VelocityCommand> feed(Agent& agent, const Event& e) {
  switch (e.kind) {
    case Event::Kind::kImu:
      return agent.onImu(e.imu);
    case Event::Kind::kDetections:
      agent.onDetections(e.detections);
      return std::nullopt;
    case Event::Kind::kGnss:
      agent.onGnss(e.gnss);
      return std::nullopt;
  }
  return std::nullopt;
}

inline std::vector<VelocityCommand> feedAll(Agent& agent, const std::vector<Event>& events) {
  std::vector<VelocityCommand> out;
  for (const Event& e : events)
    if (auto c = feed(agent, e)) out.push_back(*c);
  return out;
}

// Neighbours hover at fixed positions relative to the (not moving) focal UAV; the stream is open loop.
struct Scene {
  std::vector<std::pair<int, Vec2>> neighbours;  // id, position relative to self in the stable frame
  double heading_rad = 0.3;
  double det_noise_m = 0.0;
  double tilt_noise_rad = 0.0;
  double heading_noise_rad = 0.0;
  double gnss_noise_m = 0.0;
  bool gnss = true;
  Vec2 gnss_position_m = Vec2(12.0, -4.0);  // true position in the navigation frame
};

// `n` identified neighbours (ids 1..n) on a circle of radius `r` whose centre is `centre` relative to self.
inline Scene ringScene(int n, double r, const Vec2& centre) {
  Scene s;
  for (int j = 0; j < n; ++j) {
    const double a = 2.0 * M_PI * j / n + 0.1;
    s.neighbours.emplace_back(j + 1, centre + r * Vec2(std::cos(a), std::sin(a)));
  }
  return s;
}

// IMU at 100 Hz from t0 + 10 ms; detections and GNSS at 10 Hz, 5 ms and 7 ms after an IMU sample (so the first
// IMU sample comes before the first detection set); all interleaved in stamp order.
inline std::vector<Event> makeStream(const Scene& scene, StampNs t0, StampNs duration, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<Event> out;
  const Mat2 to_body = rotation(scene.heading_rad).transpose();
  for (StampNs tick = 1; tick * kMs <= duration; ++tick) {
    const StampNs t = t0 + tick * kMs;
    if (tick % 10 == 0) {
      Event e;
      e.kind = Event::Kind::kImu;
      e.imu.stamp_ns = t;
      e.imu.roll_rad = scene.tilt_noise_rad * normal(rng);
      e.imu.pitch_rad = scene.tilt_noise_rad * normal(rng);
      e.imu.heading_rad = scene.heading_rad + scene.heading_noise_rad * normal(rng);
      out.push_back(e);
    }
    if (tick % 100 == 15) {
      Event e;
      e.kind = Event::Kind::kDetections;
      e.detections.stamp_ns = t;
      for (const auto& [id, p] : scene.neighbours) {
        Detection d;
        d.target_id = id;
        const Vec2 noisy = p + scene.det_noise_m * Vec2(normal(rng), normal(rng));
        d.position_body_m = to_body * noisy;
        e.detections.detections.push_back(d);
      }
      out.push_back(e);
    }
    if (scene.gnss && tick % 100 == 17) {
      Event e;
      e.kind = Event::Kind::kGnss;
      e.gnss.stamp_ns = t;
      e.gnss.valid = true;
      e.gnss.position_m = scene.gnss_position_m + scene.gnss_noise_m * Vec2(normal(rng), normal(rng));
      e.gnss.std_m = std::max(scene.gnss_noise_m, 0.1);
      out.push_back(e);
    }
  }
  return out;
}

// The input tests drive the tilt input: their IMU samples are {stamp, roll, pitch, heading}, without the
// accelerometer a default agent fuses (the accelerometer's own checks: test_geometry.cpp, test_agent_input_fuzz.cpp).
inline AgentConfig configFor(Mode mode) {
  AgentConfig c;
  c.mode = mode;
  c.focal.imu_source = ImuSource::kTilt;
  return c;
}

// A detection set that adds `bad` to `good` (interleaved, so position in the set does not matter).
inline DetectionSet withBad(const DetectionSet& good, const std::vector<Detection>& bad) {
  DetectionSet out;
  out.stamp_ns = good.stamp_ns;
  std::size_t g = 0, b = 0;
  while (g < good.detections.size() || b < bad.size()) {
    if (b < bad.size()) out.detections.push_back(bad[b++]);
    if (g < good.detections.size()) out.detections.push_back(good.detections[g++]);
  }
  return out;
}

// A level IMU sample (roll, pitch and heading 0) at `stamp_ns` for `agent`: from then on it has a heading, so it takes
// detection sets.
inline void giveHeading(Agent& agent, StampNs stamp_ns = kT0) {
  ImuSample imu;
  imu.stamp_ns = stamp_ns;
  agent.onImu(imu);
}

// A detection set stamped `stamp_ns`.
inline DetectionSet detectionSet(StampNs stamp_ns, std::vector<Detection> detections = {}) {
  DetectionSet set;
  set.stamp_ns = stamp_ns;
  set.detections = std::move(detections);
  return set;
}

// `n` valid-flagged GNSS fixes stamped `stamp_ns` at the scenes' position with a plausible std (0.3 m), for a test to
// spoil one field of each.
inline std::vector<GnssSample> validFixes(std::size_t n, StampNs stamp_ns) {
  std::vector<GnssSample> fixes(n);
  for (GnssSample& g : fixes) {
    g.stamp_ns = stamp_ns;
    g.valid = true;
    g.position_m = Scene{}.gnss_position_m;
    g.std_m = 0.3;
  }
  return fixes;
}

// ---------------------------------------------------------------------------------------------------------------
// Twin agents: both are warmed up on the same 3 s stream, so they are tracking with a non-zero command.

struct Twins {
  explicit Twins(Mode mode, std::uint64_t seed = 7) : config(configFor(mode)), ref(config), dut(config) {
    Scene scene = ringScene(4, 10.0, Vec2(3.0, -2.0));
    scene.det_noise_m = 0.05;
    scene.tilt_noise_rad = 0.01;
    scene.heading_noise_rad = 0.002;
    scene.gnss_noise_m = 0.3;
    std::vector<Event> all = makeStream(scene, kT0, 5 * kSec, seed);
    const auto split = std::find_if(all.begin(), all.end(), [](const Event& e) {
      return e.kind == Event::Kind::kImu && e.imu.stamp_ns > kT0 + 3 * kSec;
    });
    const std::vector<Event> warm(all.begin(), split);
    rest.assign(split, all.end());
    for (const Event& e : warm) {
      if (auto c = feed(ref, e)) last_command = *c;
      feed(dut, e);
    }
  }

  // Feeds both agents until the next pending event is of `kind`; returns that event (still pending).
  const Event& advanceTo(Event::Kind kind) {
    while (!rest.empty() && rest.front().kind != kind) {
      if (auto c = feed(ref, rest.front())) last_command = *c;
      feed(dut, rest.front());
      rest.erase(rest.begin());
    }
    return rest.front();
  }

  Event pop() {
    Event e = rest.front();
    rest.erase(rest.begin());
    return e;
  }

  // Feeds both agents up to the next event of `kind` and takes that event off the stream, fed to neither.
  Event takeNext(Event::Kind kind) {
    advanceTo(kind);
    return pop();
  }

  // A detection set of the stream (see takeNext): `ref` gets it as it is, `dut` with the `bad` detections mixed in.
  void feedDetections(const DetectionSet& good, const std::vector<Detection>& bad) {
    dut.onDetections(withBad(good, bad));
    ref.onDetections(good);
  }

  StampNs nextStamp(Event::Kind kind) const {
    for (const Event& e : rest) {
      if (e.kind != kind) continue;
      switch (kind) {
        case Event::Kind::kImu:
          return e.imu.stamp_ns;
        case Event::Kind::kDetections:
          return e.detections.stamp_ns;
        case Event::Kind::kGnss:
          return e.gnss.stamp_ns;
      }
    }
    return 0;
  }

  // THEN-part shared by every rejection test: the rest of the stream gives bit-identical commands and state.
  // `extra_commands` is the number of rejected IMU samples `dut` answered on top of `ref`.
  void expectNoLastingEffect(std::uint64_t extra_commands) {
    expectSameState(ref, dut, /*with_counters=*/false, /*with_commands=*/false);
    EXPECT_EQ(dut.diagnostics().commands, ref.diagnostics().commands + extra_commands);
    const RejectCounters before = dut.diagnostics().rejected;
    std::size_t compared = 0;
    for (const Event& e : rest) {
      const auto a = feed(ref, e);
      const auto b = feed(dut, e);
      if (a && b) {
        ++compared;
        EXPECT_TRUE(sameBits(a->velocity_mps, b->velocity_mps))
            << "command at " << a->stamp_ns << ": " << a->velocity_mps.transpose() << " vs "
            << b->velocity_mps.transpose();
        EXPECT_EQ(b->seq, a->seq + extra_commands);
      }
    }
    EXPECT_GT(compared, 100u);
    expectSameState(ref, dut, /*with_counters=*/false, /*with_commands=*/false);
    // The continuation was clean: no counter moved after the bad input.
    expectCounters(dut.diagnostics().rejected, before);
    expectCounters(ref.diagnostics().rejected, RejectCounters{});
  }

  // The THEN of a rejection test: `dut` counted exactly `n` rejections, all in `counter`, and the rest of the stream
  // shows no lasting effect (expectNoLastingEffect, with `extra_commands` answered rejected IMU samples).
  void expectOnlyRejected(std::uint64_t RejectCounters::*counter, std::uint64_t n, std::uint64_t extra_commands) {
    expectCounters(dut.diagnostics().rejected, only(counter, n));
    expectNoLastingEffect(extra_commands);
  }

  void expectWarmedUp() const {
    ASSERT_EQ(ref.diagnostics().rejected.total(), 0u);
    ASSERT_EQ(dut.diagnostics().rejected.total(), 0u);
    ASSERT_EQ(ref.diagnostics().stage, Stage::kTracking);
    ASSERT_GT(last_command.velocity_mps.norm(), 0.01) << "warm-up must leave a non-trivial command";
  }

  AgentConfig config;
  Agent ref;
  Agent dut;
  std::vector<Event> rest;
  VelocityCommand last_command;
};

inline Detection det(int id, double x, double y) {
  Detection d;
  d.target_id = id;
  d.position_body_m = Vec2(x, y);
  return d;
}

inline Detection det(int id, double x, double y, const Mat2& cov) {
  Detection d = det(id, x, y);
  d.covariance_m2 = cov;
  return d;
}

inline Mat2 mat(double a, double b, double c, double d) {
  Mat2 m;
  m << a, b, c, d;
  return m;
}

inline bool finiteDiagnostics(const Diagnostics& d) {
  return d.position_m.allFinite() && d.velocity_mps.allFinite() && d.position_cov_m2.allFinite() &&
         d.velocity_cov_m2ps2.allFinite() && d.frame_centre_m.allFinite();
}

inline bool finiteTracks(const TrackBank& bank) {
  for (const Track& t : bank.tracks())
    if (!t.estimate.x.allFinite() || !t.estimate.P.allFinite()) return false;
  return true;
}

// Runs `body` in a forked child under a deadline, so that a hang inside the agent (an infinite loop) becomes a test
// failure instead of a stuck test binary. Returns "" when the child finished in time, otherwise what happened.
template <typename F>
std::string runWithDeadline(unsigned seconds, F&& body) {
  std::fflush(nullptr);
  const pid_t pid = ::fork();
  if (pid < 0) return "fork() failed";
  if (pid == 0) {
    ::alarm(seconds);
    body();
    std::_Exit(0);
  }
  int status = 0;
  if (::waitpid(pid, &status, 0) != pid) return "waitpid() failed";
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0) return "";
  if (WIFSIGNALED(status) && WTERMSIG(status) == SIGALRM) {
    return "did not finish within " + std::to_string(seconds) + " s: the agent hangs";
  }
  return "child ended abnormally, wait status " + std::to_string(status);
}

}  // namespace swa::agent::testing

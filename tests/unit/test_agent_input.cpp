// Bad input at the Agent facade (issue spec): non-finite numbers, stamps that go backwards, detection sets larger
// than limits.max_detections and out-of-range IDs are rejected and counted in Diagnostics::rejected, and the
// command is always finite and within saturation whatever comes in. Also: the facade is deterministic, bit for bit.
//
// Each rejection test runs two agents on the same realistic stream: `ref` never sees the bad input, `dut` does.
// The test then asserts that exactly one counter moved, by the exact amount, and that the rest of the agent (track
// bank, both focal filters, diagnostics and every later command) is bit-identical to `ref`.

#include <algorithm>
#include <climits>
#include <cmath>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include "swa/agent/agent.h"

namespace swa::agent {
namespace {

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr StampNs kMs = 1'000'000;
constexpr StampNs kSec = 1'000'000'000;
constexpr StampNs kT0 = 5 * kSec;  // streams start here

// ---------------------------------------------------------------------------------------------------------------
// Bitwise comparison helpers: "no effect" and "deterministic" mean the same bits (-0.0 != 0.0), not NEAR.

bool sameBits(double a, double b) {
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

bool sameCommand(const VelocityCommand& a, const VelocityCommand& b) {
  return a.stamp_ns == b.stamp_ns && a.answered_stamp_ns == b.answered_stamp_ns && a.seq == b.seq &&
         sameBits(a.velocity_mps, b.velocity_mps);
}

// ---------------------------------------------------------------------------------------------------------------
// Counters.

RejectCounters only(std::uint64_t RejectCounters::*field, std::uint64_t n) {
  RejectCounters c;
  c.*field = n;
  return c;
}

void expectCounters(const RejectCounters& got, const RejectCounters& want) {
  EXPECT_EQ(got.nonfinite, want.nonfinite) << "rejected.nonfinite";
  EXPECT_EQ(got.out_of_order, want.out_of_order) << "rejected.out_of_order";
  EXPECT_EQ(got.oversize, want.oversize) << "rejected.oversize";
  EXPECT_EQ(got.bad_id, want.bad_id) << "rejected.bad_id";
  EXPECT_EQ(got.implausible, want.implausible) << "rejected.implausible";
  EXPECT_EQ(got.no_heading, want.no_heading) << "rejected.no_heading";
}

// ---------------------------------------------------------------------------------------------------------------
// State comparison: everything observable about an agent except the reject counters (and, when an IMU sample was
// rejected, the command count that every answered IMU sample increments).

void expectSameFilter(const FocalEstimator& a, const FocalEstimator& b, const char* what) {
  EXPECT_EQ(a.initialized(), b.initialized()) << what;
  EXPECT_EQ(a.time(), b.time()) << what;
  EXPECT_TRUE(sameBits(a.state().x, b.state().x)) << what << " x differs:\n" << a.state().x << "\nvs\n" << b.state().x;
  EXPECT_TRUE(sameBits(a.state().P, b.state().P)) << what << " P differs";
}

void expectSameTracks(const TrackBank& a, const TrackBank& b) {
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

void expectSameDiagnostics(const Diagnostics& a, const Diagnostics& b, bool with_counters, bool with_commands) {
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

void expectSameState(const Agent& a, const Agent& b, bool with_counters, bool with_commands) {
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

std::optional<VelocityCommand> feed(Agent& agent, const Event& e) {
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

std::vector<VelocityCommand> feedAll(Agent& agent, const std::vector<Event>& events) {
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
Scene ringScene(int n, double r, const Vec2& centre) {
  Scene s;
  for (int j = 0; j < n; ++j) {
    const double a = 2.0 * M_PI * j / n + 0.1;
    s.neighbours.emplace_back(j + 1, centre + r * Vec2(std::cos(a), std::sin(a)));
  }
  return s;
}

// IMU at 100 Hz from t0 + 10 ms; detections and GNSS at 10 Hz, 5 ms and 7 ms after an IMU sample (so the first
// IMU sample comes before the first detection set); all interleaved in stamp order.
std::vector<Event> makeStream(const Scene& scene, StampNs t0, StampNs duration, std::uint64_t seed) {
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

AgentConfig configFor(Mode mode) {
  AgentConfig c;
  c.mode = mode;
  return c;
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

Detection det(int id, double x, double y) {
  Detection d;
  d.target_id = id;
  d.position_body_m = Vec2(x, y);
  return d;
}

Detection det(int id, double x, double y, const Mat2& cov) {
  Detection d = det(id, x, y);
  d.covariance_m2 = cov;
  return d;
}

Mat2 mat(double a, double b, double c, double d) {
  Mat2 m;
  m << a, b, c, d;
  return m;
}

// A detection set that adds `bad` to `good` (interleaved, so position in the set does not matter).
DetectionSet withBad(const DetectionSet& good, const std::vector<Detection>& bad) {
  DetectionSet out;
  out.stamp_ns = good.stamp_ns;
  std::size_t g = 0, b = 0;
  while (g < good.detections.size() || b < bad.size()) {
    if (b < bad.size()) out.detections.push_back(bad[b++]);
    if (g < good.detections.size()) out.detections.push_back(good.detections[g++]);
  }
  return out;
}

// ===============================================================================================================
// IMU

TEST(AgentInputImu, NonFiniteAttitudeIsCountedAsNonfiniteAndChangesNothing) {
  // GIVEN two anchored agents tracking on the same stream
  Twins tw(Mode::kAnchored);
  ASSERT_NO_FATAL_FAILURE(tw.expectWarmedUp());
  const StampNs next = tw.nextStamp(Event::Kind::kImu);
  const Vec2 previous = tw.last_command.velocity_mps;

  // WHEN one of them gets IMU samples with a NaN roll, an inf pitch, a NaN heading, a -inf heading (each with the
  // stamp of the next good sample, so a consumed stamp would show up as an out_of_order later)
  std::vector<ImuSample> bad(4);
  bad[0].roll_rad = kNan;
  bad[1].pitch_rad = kInf;
  bad[2].heading_rad = kNan;
  bad[3].heading_rad = -kInf;
  for (ImuSample& s : bad) {
    s.stamp_ns = next;
    const VelocityCommand c = tw.dut.onImu(s);
    // THEN each is still answered, with the previous command, which is finite
    EXPECT_TRUE(sameBits(c.velocity_mps, previous)) << c.velocity_mps.transpose() << " vs " << previous.transpose();
    EXPECT_TRUE(allFinite(c.velocity_mps));
  }

  // THEN exactly nonfinite went up, by 4, and nothing else changed
  expectCounters(tw.dut.diagnostics().rejected, only(&RejectCounters::nonfinite, 4));
  tw.expectNoLastingEffect(4);
}

TEST(AgentInputImu, TiltBeyondLimitIsCountedAsImplausibleAndChangesNothing) {
  // GIVEN two anchored agents tracking on the same stream, max_tilt_rad = 0.8
  Twins tw(Mode::kAnchored);
  ASSERT_NO_FATAL_FAILURE(tw.expectWarmedUp());
  const double max_tilt = tw.config.limits.max_tilt_rad;
  const StampNs next = tw.nextStamp(Event::Kind::kImu);
  const Vec2 previous = tw.last_command.velocity_mps;

  // WHEN one of them gets finite IMU samples with |roll| or |pitch| just above, and far above, the limit
  std::vector<ImuSample> bad(5);
  bad[0].roll_rad = std::nextafter(max_tilt, 1.0);
  bad[1].roll_rad = -1.2;
  bad[2].pitch_rad = std::nextafter(-max_tilt, -1.0);
  bad[3].pitch_rad = 1e300;
  bad[4].roll_rad = 0.9;
  bad[4].pitch_rad = -0.9;
  for (ImuSample& s : bad) {
    s.stamp_ns = next;
    s.heading_rad = 0.3;
    const VelocityCommand c = tw.dut.onImu(s);
    EXPECT_TRUE(sameBits(c.velocity_mps, previous));
  }

  // THEN exactly implausible went up, by 5, and nothing else changed
  expectCounters(tw.dut.diagnostics().rejected, only(&RejectCounters::implausible, 5));
  tw.expectNoLastingEffect(5);
}

TEST(AgentInputImu, TiltExactlyAtLimitIsAccepted) {
  // GIVEN a fresh agent
  Agent agent(configFor(Mode::kSwa));
  const double max_tilt = agent.config().limits.max_tilt_rad;
  // WHEN IMU samples have |roll| and |pitch| exactly at the limit
  ImuSample s;
  s.stamp_ns = kT0;
  s.roll_rad = max_tilt;
  s.pitch_rad = -max_tilt;
  agent.onImu(s);
  // THEN nothing is rejected, and the sample gave a heading (a detection set is accepted afterwards)
  DetectionSet d;
  d.stamp_ns = kT0 + kMs;
  d.detections.push_back(det(1, 5.0, 0.0));
  agent.onDetections(d);
  expectCounters(agent.diagnostics().rejected, RejectCounters{});
  EXPECT_NE(agent.bank().find(1), nullptr);
}

TEST(AgentInputImu, StampNotAfterPreviousIsOutOfOrderAndAnsweredWithPreviousCommand) {
  // GIVEN two anchored agents tracking on the same stream, the last IMU at stamp T
  Twins tw(Mode::kAnchored);
  ASSERT_NO_FATAL_FAILURE(tw.expectWarmedUp());
  const StampNs last = tw.last_command.stamp_ns;
  const Vec2 previous = tw.last_command.velocity_mps;
  const std::uint64_t seq = tw.dut.diagnostics().commands;

  // WHEN one of them gets valid-looking IMU samples stamped T (equal), T - 1 ns and T - 1 s, with an attitude that
  // would change the command if used
  const StampNs stamps[] = {last, last - 1, last - kSec};
  for (StampNs st : stamps) {
    ImuSample s;
    s.stamp_ns = st;
    s.roll_rad = 0.5;
    s.pitch_rad = -0.5;
    s.heading_rad = 2.0;
    const VelocityCommand c = tw.dut.onImu(s);
    // THEN each is answered with exactly the previous command, finite and within saturation
    EXPECT_TRUE(sameBits(c.velocity_mps, previous)) << c.velocity_mps.transpose() << " vs " << previous.transpose();
    EXPECT_TRUE(allFinite(c.velocity_mps));
    EXPECT_LE(c.velocity_mps.norm(), tw.config.control.v_max_mps);
    EXPECT_EQ(c.answered_stamp_ns, st);
  }
  EXPECT_EQ(tw.dut.diagnostics().commands, seq + 3);

  // THEN exactly out_of_order went up, by 3, and nothing else changed
  expectCounters(tw.dut.diagnostics().rejected, only(&RejectCounters::out_of_order, 3));
  tw.expectNoLastingEffect(3);
}

TEST(AgentInputImu, RejectedImuBeforeAnyGoodOneAnswersWithZeroCommand) {
  // GIVEN a fresh agent
  Agent agent(configFor(Mode::kAnchored));
  // WHEN its very first IMU samples are non-finite / implausible
  ImuSample a;
  a.stamp_ns = kT0;
  a.roll_rad = kNan;
  ImuSample b;
  b.stamp_ns = kT0 + kMs;
  b.pitch_rad = 3.0;
  const VelocityCommand ca = agent.onImu(a);
  const VelocityCommand cb = agent.onImu(b);
  // THEN they are answered with a hover command and counted once each
  EXPECT_TRUE(sameBits(ca.velocity_mps, Vec2::Zero()));
  EXPECT_TRUE(sameBits(cb.velocity_mps, Vec2::Zero()));
  RejectCounters want;
  want.nonfinite = 1;
  want.implausible = 1;
  expectCounters(agent.diagnostics().rejected, want);
  EXPECT_EQ(agent.diagnostics().commands, 2u);
  EXPECT_EQ(cb.seq, ca.seq + 1);
}

// ===============================================================================================================
// Detections

TEST(AgentInputDetections, SetLargerThanBoundIsRejectedWholeOncePerSet) {
  // GIVEN an agent with a heading and no tracks, limits.max_detections = 64
  Agent agent(configFor(Mode::kSwa));
  ImuSample imu;
  imu.stamp_ns = kT0;
  agent.onImu(imu);
  const std::size_t max = agent.config().limits.max_detections;
  ASSERT_EQ(max, 64u);

  // WHEN two sets of 65 valid, distinct detections arrive
  for (int k = 0; k < 2; ++k) {
    DetectionSet big;
    big.stamp_ns = kT0 + (k + 1) * kMs;
    for (std::size_t i = 0; i <= max; ++i) {
      big.detections.push_back(det(static_cast<int>(i), 5.0 + static_cast<double>(i), 1.0));
    }
    agent.onDetections(big);
  }

  // THEN oversize counts 1 per set (2), nothing else, and nothing is tracked
  expectCounters(agent.diagnostics().rejected, only(&RejectCounters::oversize, 2));
  EXPECT_TRUE(agent.bank().tracks().empty());
  EXPECT_EQ(agent.diagnostics().tentative_tracks, 0);
  EXPECT_EQ(agent.diagnostics().confirmed_tracks, 0);

  // AND a valid set with the same stamp as a rejected one is still accepted (the stamp was not consumed)
  DetectionSet small;
  small.stamp_ns = kT0 + 2 * kMs;
  small.detections.push_back(det(3, 4.0, 0.0));
  agent.onDetections(small);
  expectCounters(agent.diagnostics().rejected, only(&RejectCounters::oversize, 2));
  EXPECT_NE(agent.bank().find(3), nullptr);
}

TEST(AgentInputDetections, OversizeSetChangesNothingInATrackingAgent) {
  // GIVEN two anchored agents tracking on the same stream
  Twins tw(Mode::kAnchored);
  ASSERT_NO_FATAL_FAILURE(tw.expectWarmedUp());
  const DetectionSet good = tw.advanceTo(Event::Kind::kDetections).detections;
  // WHEN one gets, before the next good set, a set of 65 detections of the known neighbours with the same stamp
  DetectionSet big;
  big.stamp_ns = good.stamp_ns;
  while (big.detections.size() <= tw.config.limits.max_detections)
    for (const Detection& d : good.detections) big.detections.push_back(d);
  big.detections.resize(tw.config.limits.max_detections + 1);
  tw.dut.onDetections(big);
  // THEN oversize == 1 and nothing else changed
  expectCounters(tw.dut.diagnostics().rejected, only(&RejectCounters::oversize, 1));
  tw.expectNoLastingEffect(0);
}

TEST(AgentInputDetections, SetOfExactlyTheBoundIsAccepted) {
  // GIVEN an agent with a heading
  Agent agent(configFor(Mode::kSwa));
  ImuSample imu;
  imu.stamp_ns = kT0;
  agent.onImu(imu);
  // WHEN a set of exactly 64 valid detections with distinct IDs arrives
  DetectionSet set;
  set.stamp_ns = kT0 + kMs;
  for (int i = 0; i < 64; ++i) set.detections.push_back(det(i, 5.0 + i, -2.0));
  agent.onDetections(set);
  // THEN nothing is rejected and all 64 are tracked (tentative)
  expectCounters(agent.diagnostics().rejected, RejectCounters{});
  EXPECT_EQ(agent.bank().tracks().size(), 64u);
  EXPECT_EQ(agent.diagnostics().tentative_tracks, 64);
  for (int i = 0; i < 64; ++i) EXPECT_NE(agent.bank().find(i), nullptr) << i;
}

TEST(AgentInputDetections, NonFinitePositionDropsOnlyThatDetection) {
  // GIVEN two anchored agents tracking on the same stream
  Twins tw(Mode::kAnchored);
  ASSERT_NO_FATAL_FAILURE(tw.expectWarmedUp());
  const DetectionSet set = tw.advanceTo(Event::Kind::kDetections).detections;
  tw.pop();
  // WHEN one gets the next set with extra detections of new IDs 20..23 with NaN x, inf y, -inf x, NaN both, and
  // the other the set without them
  const std::vector<Detection> bad = {det(20, kNan, 1.0), det(21, 1.0, kInf), det(22, -kInf, 0.0),
                                      det(23, kNan, kNan)};
  tw.dut.onDetections(withBad(set, bad));
  tw.ref.onDetections(set);
  // THEN nonfinite == 4, nothing else; the bad IDs are not tracked and the good detections of the same set were used
  expectCounters(tw.dut.diagnostics().rejected, only(&RejectCounters::nonfinite, 4));
  for (int id = 20; id <= 23; ++id) EXPECT_EQ(tw.dut.bank().find(id), nullptr) << id;
  for (const Detection& d : set.detections) {
    const Track* t = tw.dut.bank().find(d.target_id);
    ASSERT_NE(t, nullptr);
    EXPECT_EQ(t->last_detection_ns, set.stamp_ns) << "good detection " << d.target_id << " of the set not used";
  }
  tw.expectNoLastingEffect(0);
}

TEST(AgentInputDetections, NonFiniteCovarianceIsNonfinite) {
  // GIVEN two anchored agents tracking on the same stream
  Twins tw(Mode::kAnchored);
  ASSERT_NO_FATAL_FAILURE(tw.expectWarmedUp());
  const DetectionSet set = tw.advanceTo(Event::Kind::kDetections).detections;
  tw.pop();
  // WHEN one gets the next set with extra detections (valid positions, new IDs) whose covariance has a NaN
  // (diagonal, off-diagonal), an inf, or is all NaN
  const std::vector<Detection> bad = {
      det(20, 3.0, 1.0, mat(kNan, 0.0, 0.0, 0.1)), det(21, 3.0, 1.0, mat(0.1, kNan, kNan, 0.1)),
      det(22, 3.0, 1.0, mat(0.1, 0.0, 0.0, kInf)), det(23, 3.0, 1.0, Mat2::Constant(kNan)),
      // an existing neighbour's ID: the bad covariance must not touch its track either
      det(set.detections.front().target_id, set.detections.front().position_body_m.x(),
          set.detections.front().position_body_m.y(), mat(0.1, 0.0, 0.0, kNan))};
  tw.dut.onDetections(withBad(set, bad));
  tw.ref.onDetections(set);
  // THEN nonfinite == 5, nothing else, and no effect
  expectCounters(tw.dut.diagnostics().rejected, only(&RejectCounters::nonfinite, 5));
  for (int id = 20; id <= 23; ++id) EXPECT_EQ(tw.dut.bank().find(id), nullptr) << id;
  tw.expectNoLastingEffect(0);
}

TEST(AgentInputDetections, NonSpdCovarianceIsImplausible) {
  // GIVEN two anchored agents tracking on the same stream
  Twins tw(Mode::kAnchored);
  ASSERT_NO_FATAL_FAILURE(tw.expectWarmedUp());
  const DetectionSet set = tw.advanceTo(Event::Kind::kDetections).detections;
  tw.pop();
  // WHEN one gets the next set with extra detections whose covariance is finite but not a covariance: negative
  // variance (first, second, both), asymmetric, symmetric indefinite, zero, and positive semi-definite (singular)
  const std::vector<Detection> bad = {
      det(20, 3.0, 1.0, mat(-0.1, 0.0, 0.0, 0.1)), det(21, 3.0, 1.0, mat(0.1, 0.0, 0.0, -0.1)),
      det(22, 3.0, 1.0, mat(-0.1, 0.0, 0.0, -0.1)), det(23, 3.0, 1.0, mat(0.1, 0.05, -0.05, 0.1)),
      det(24, 3.0, 1.0, mat(0.1, 0.5, 0.5, 0.1)),   det(25, 3.0, 1.0, Mat2::Zero()),
      det(26, 3.0, 1.0, mat(0.1, 0.1, 0.1, 0.1))};
  tw.dut.onDetections(withBad(set, bad));
  tw.ref.onDetections(set);
  // THEN implausible == 7, nothing else, and no effect
  expectCounters(tw.dut.diagnostics().rejected, only(&RejectCounters::implausible, 7));
  for (int id = 20; id <= 26; ++id) EXPECT_EQ(tw.dut.bank().find(id), nullptr) << id;
  tw.expectNoLastingEffect(0);
}

TEST(AgentInputDetections, PositionBeyondLimitIsImplausible) {
  // GIVEN two anchored agents tracking on the same stream, max_abs_position_m = 1e6
  Twins tw(Mode::kAnchored);
  ASSERT_NO_FATAL_FAILURE(tw.expectWarmedUp());
  const double max_pos = tw.config.limits.max_abs_position_m;
  const DetectionSet set = tw.advanceTo(Event::Kind::kDetections).detections;
  tw.pop();
  // WHEN one gets extra detections farther than the limit (just beyond on an axis, diagonally, 1e300, and DBL_MAX
  // whose norm overflows)
  const double big = std::numeric_limits<double>::max();
  const std::vector<Detection> bad = {det(20, std::nextafter(max_pos, 2e6), 0.0), det(21, 0.0, -2e6),
                                      det(22, 0.75e6, -0.75e6), det(23, 1e300, 1e300), det(24, big, -big),
                                      det(kAnonymousId, 1e300, 0.0)};
  tw.dut.onDetections(withBad(set, bad));
  tw.ref.onDetections(set);
  // THEN implausible == 6, nothing else, and no effect
  expectCounters(tw.dut.diagnostics().rejected, only(&RejectCounters::implausible, 6));
  tw.expectNoLastingEffect(0);
}

TEST(AgentInputDetections, PositionAtLimitIsAcceptedButNotANeighbour) {
  // GIVEN an agent with a heading
  Agent agent(configFor(Mode::kSwa));
  ImuSample imu;
  imu.stamp_ns = kT0;
  agent.onImu(imu);
  // WHEN a detection lies exactly at max_abs_position_m
  DetectionSet set;
  set.stamp_ns = kT0 + kMs;
  set.detections.push_back(det(9, agent.config().limits.max_abs_position_m, 0.0));
  agent.onDetections(set);
  // THEN it is accepted and tracked
  expectCounters(agent.diagnostics().rejected, RejectCounters{});
  EXPECT_NE(agent.bank().find(9), nullptr);
  EXPECT_EQ(agent.diagnostics().neighbour_count, 0);
}

TEST(AgentInputDetections, IdOutsideRangeIsBadId) {
  // GIVEN two anchored agents tracking on the same stream, max_target_id = 1'000'000
  Twins tw(Mode::kAnchored);
  ASSERT_NO_FATAL_FAILURE(tw.expectWarmedUp());
  const int max_id = tw.config.limits.max_target_id;
  const DetectionSet set = tw.advanceTo(Event::Kind::kDetections).detections;
  tw.pop();
  // WHEN one gets extra, otherwise valid detections with IDs -2, -1000, INT_MIN, max+1, INT_MAX and the first
  // anonymous track id
  const std::vector<Detection> bad = {det(-2, 3.0, 1.0),          det(-1000, 3.0, 1.0),
                                      det(INT_MIN, 3.0, 1.0),     det(max_id + 1, 3.0, 1.0),
                                      det(INT_MAX, 3.0, 1.0),     det(kFirstAnonymousTrackId, 3.0, 1.0)};
  tw.dut.onDetections(withBad(set, bad));
  tw.ref.onDetections(set);
  // THEN bad_id == 6, nothing else, and no effect
  expectCounters(tw.dut.diagnostics().rejected, only(&RejectCounters::bad_id, 6));
  tw.expectNoLastingEffect(0);
}

TEST(AgentInputDetections, IdsAtTheEdgesOfTheRangeAreAccepted) {
  // GIVEN an agent with a heading
  Agent agent(configFor(Mode::kSwa));
  ImuSample imu;
  imu.stamp_ns = kT0;
  agent.onImu(imu);
  // WHEN detections with IDs 0, max_target_id and anonymous (-1) arrive
  DetectionSet set;
  set.stamp_ns = kT0 + kMs;
  set.detections = {det(0, 5.0, 0.0), det(agent.config().limits.max_target_id, 0.0, 5.0),
                    det(kAnonymousId, -5.0, 0.0)};
  agent.onDetections(set);
  // THEN nothing is rejected and three tracks exist
  expectCounters(agent.diagnostics().rejected, RejectCounters{});
  EXPECT_NE(agent.bank().find(0), nullptr);
  EXPECT_NE(agent.bank().find(agent.config().limits.max_target_id), nullptr);
  EXPECT_EQ(agent.bank().tracks().size(), 3u);
}

TEST(AgentInputDetections, DetectionsBeforeAnyAcceptedImuHaveNoHeading) {
  // GIVEN a fresh agent (no IMU sample yet)
  Agent agent(configFor(Mode::kSwa));
  DetectionSet set;
  set.stamp_ns = kT0;
  set.detections = {det(1, 5.0, 0.0), det(2, 0.0, 5.0)};

  // WHEN a valid set of two detections arrives
  agent.onDetections(set);
  // THEN no_heading counts the set once, nothing is tracked
  expectCounters(agent.diagnostics().rejected, only(&RejectCounters::no_heading, 1));
  EXPECT_TRUE(agent.bank().tracks().empty());

  // WHEN a rejected IMU sample (NaN heading) arrives and then the set again
  ImuSample bad;
  bad.stamp_ns = kT0 + kMs;
  bad.heading_rad = kNan;
  agent.onImu(bad);
  agent.onDetections(set);
  // THEN the rejected IMU did not give a heading either
  RejectCounters want;
  want.no_heading = 2;
  want.nonfinite = 1;
  expectCounters(agent.diagnostics().rejected, want);
  EXPECT_TRUE(agent.bank().tracks().empty());

  // WHEN a good IMU sample arrives, then the same set with the same stamp
  ImuSample good;
  good.stamp_ns = kT0 + 2 * kMs;
  agent.onImu(good);
  agent.onDetections(set);
  // THEN it is accepted (the no_heading rejections did not consume the stamp)
  expectCounters(agent.diagnostics().rejected, want);
  EXPECT_EQ(agent.bank().tracks().size(), 2u);
}

TEST(AgentInputDetections, SetStampNotIncreasingIsOutOfOrder) {
  // GIVEN two anchored agents tracking on the same stream, the last accepted detection set stamped T
  Twins tw(Mode::kAnchored);
  ASSERT_NO_FATAL_FAILURE(tw.expectWarmedUp());
  const Event next = tw.advanceTo(Event::Kind::kDetections);
  tw.pop();
  tw.ref.onDetections(next.detections);
  tw.dut.onDetections(next.detections);
  const StampNs last = next.detections.stamp_ns;

  // WHEN one gets valid sets stamped T (equal), T - 1 ns and T - 2 s, with shifted positions that would move the
  // tracks if used
  for (StampNs st : {last, last - 1, last - 2 * kSec}) {
    DetectionSet s = next.detections;
    s.stamp_ns = st;
    for (Detection& d : s.detections) d.position_body_m += Vec2(1.0, 1.0);
    tw.dut.onDetections(s);
  }
  // THEN out_of_order == 3 (once per set), nothing else, and no effect
  expectCounters(tw.dut.diagnostics().rejected, only(&RejectCounters::out_of_order, 3));
  tw.expectNoLastingEffect(0);
}

TEST(AgentInputDetections, SetOlderThanLatestImuIsNotOutOfOrder) {
  // GIVEN an agent whose IMU is at T
  Agent agent(configFor(Mode::kSwa));
  ImuSample imu;
  imu.stamp_ns = kT0 + 100 * kMs;
  agent.onImu(imu);
  // WHEN a detection set stamped 50 ms before T arrives (sensor latency; stamps are ordered per stream)
  DetectionSet set;
  set.stamp_ns = kT0 + 50 * kMs;
  set.detections = {det(1, 5.0, 0.0)};
  agent.onDetections(set);
  // THEN it is accepted
  expectCounters(agent.diagnostics().rejected, RejectCounters{});
  EXPECT_NE(agent.bank().find(1), nullptr);
}

// ===============================================================================================================
// GNSS

TEST(AgentInputGnss, ValidFixWithNonFiniteValuesIsNonfinite) {
  // GIVEN two anchored agents tracking on the same stream (GNSS in use)
  Twins tw(Mode::kAnchored);
  ASSERT_NO_FATAL_FAILURE(tw.expectWarmedUp());
  const StampNs next = tw.nextStamp(Event::Kind::kGnss);
  ASSERT_TRUE(tw.dut.diagnostics().gnss_valid);
  // WHEN one gets valid-flagged fixes with NaN x, inf y, NaN std, inf std (stamped like the next good fix)
  std::vector<GnssSample> bad(4);
  for (GnssSample& g : bad) {
    g.stamp_ns = next;
    g.valid = true;
    g.position_m = Vec2(12.0, -4.0);
    g.std_m = 0.3;
  }
  bad[0].position_m.x() = kNan;
  bad[1].position_m.y() = kInf;
  bad[2].std_m = kNan;
  bad[3].std_m = kInf;
  for (const GnssSample& g : bad) tw.dut.onGnss(g);
  // THEN nonfinite == 4, nothing else, and no effect
  expectCounters(tw.dut.diagnostics().rejected, only(&RejectCounters::nonfinite, 4));
  tw.expectNoLastingEffect(0);
}

TEST(AgentInputGnss, NonPositiveStdOrFarPositionIsImplausible) {
  // GIVEN two anchored agents tracking on the same stream
  Twins tw(Mode::kAnchored);
  ASSERT_NO_FATAL_FAILURE(tw.expectWarmedUp());
  const StampNs next = tw.nextStamp(Event::Kind::kGnss);
  // WHEN one gets valid-flagged fixes with std 0, -0, -1, and a position beyond max_abs_position_m (1e6 + 1 and
  // 1e300)
  std::vector<GnssSample> bad(5);
  for (GnssSample& g : bad) {
    g.stamp_ns = next;
    g.valid = true;
    g.position_m = Vec2(12.0, -4.0);
    g.std_m = 0.3;
  }
  bad[0].std_m = 0.0;
  bad[1].std_m = -0.0;
  bad[2].std_m = -1.0;
  bad[3].position_m = Vec2(tw.config.limits.max_abs_position_m + 1.0, 0.0);
  bad[4].position_m = Vec2(1e300, 1e300);
  for (const GnssSample& g : bad) tw.dut.onGnss(g);
  // THEN implausible == 5, nothing else, and no effect
  expectCounters(tw.dut.diagnostics().rejected, only(&RejectCounters::implausible, 5));
  tw.expectNoLastingEffect(0);
}

TEST(AgentInputGnss, StampNotAfterPreviousIsOutOfOrder) {
  // GIVEN two anchored agents tracking on the same stream, last fix at T
  Twins tw(Mode::kAnchored);
  ASSERT_NO_FATAL_FAILURE(tw.expectWarmedUp());
  const Event next = tw.advanceTo(Event::Kind::kGnss);
  tw.pop();
  tw.ref.onGnss(next.gnss);
  tw.dut.onGnss(next.gnss);
  // WHEN one gets valid fixes stamped T, T - 1 ns and T - 3 s that would pull the estimate 5 m if used, and one
  // invalid fix stamped T - 1 ns
  for (StampNs st : {next.gnss.stamp_ns, next.gnss.stamp_ns - 1, next.gnss.stamp_ns - 3 * kSec}) {
    GnssSample g = next.gnss;
    g.stamp_ns = st;
    g.position_m += Vec2(5.0, 0.0);
    tw.dut.onGnss(g);
  }
  GnssSample lost = next.gnss;
  lost.stamp_ns = next.gnss.stamp_ns - 1;
  lost.valid = false;
  tw.dut.onGnss(lost);
  // THEN out_of_order == 4, nothing else, and no effect (the stale invalid fix did not clear gnss_valid either)
  expectCounters(tw.dut.diagnostics().rejected, only(&RejectCounters::out_of_order, 4));
  EXPECT_TRUE(tw.dut.diagnostics().gnss_valid);
  tw.expectNoLastingEffect(0);
}

TEST(AgentInputGnss, InvalidFixWithGarbageFieldsIsNotAnError) {
  // GIVEN two anchored agents tracking on the same stream
  Twins tw(Mode::kAnchored);
  ASSERT_NO_FATAL_FAILURE(tw.expectWarmedUp());
  const Event next = tw.advanceTo(Event::Kind::kGnss);
  tw.pop();
  // WHEN the receiver loses its fix: `dut` gets valid=false with NaN / inf / negative garbage in every field, `ref`
  // gets valid=false with clean zeros, both at the same stamp
  GnssSample garbage;
  garbage.stamp_ns = next.gnss.stamp_ns;
  garbage.valid = false;
  garbage.position_m = Vec2(kNan, -kInf);
  garbage.std_m = kNan;
  GnssSample clean;  // default position and std
  clean.stamp_ns = next.gnss.stamp_ns;
  clean.valid = false;
  tw.dut.onGnss(garbage);
  tw.ref.onGnss(clean);
  // THEN nothing is rejected, both report no valid GNSS (diagnostics are refreshed by the next IMU sample), the
  // estimate is finite, and the garbage had no effect beyond "no fix": the agents stay bit-identical from here on
  expectCounters(tw.dut.diagnostics().rejected, RejectCounters{});
  const Event imu = tw.advanceTo(Event::Kind::kImu);
  tw.pop();
  feed(tw.ref, imu);
  feed(tw.dut, imu);
  EXPECT_FALSE(tw.dut.diagnostics().gnss_valid);
  EXPECT_TRUE(allFinite(tw.dut.diagnostics().position_m));
  EXPECT_TRUE(allFinite(tw.dut.diagnostics().position_cov_m2));
  // More lost fixes, each with garbage, then the receiver recovers (the rest of the stream has valid fixes).
  for (int i = 1; i <= 3; ++i) {
    garbage.stamp_ns = next.gnss.stamp_ns + i;
    garbage.std_m = -kInf;
    clean.stamp_ns = garbage.stamp_ns;
    tw.dut.onGnss(garbage);
    tw.ref.onGnss(clean);
  }
  expectCounters(tw.dut.diagnostics().rejected, RejectCounters{});
  tw.expectNoLastingEffect(0);
  EXPECT_TRUE(tw.dut.diagnostics().gnss_valid) << "the later valid fixes must be used again";
}

// A fix whose std is finite and positive but absurd (1e300 m): its variance overflows to inf. The counter docs list
// "GNSS std" under implausible ("finite but physically impossible"), so it is rejected and counted like std <= 0,
// and above all it must not wreck the absolute estimator.
TEST(AgentInputGnss, AbsurdStdDoesNotPoisonTheAbsoluteEstimator) {
  for (const bool first_fix : {true, false}) {
    SCOPED_TRACE(first_fix ? "absurd std on the very first (hold-point) fix" : "absurd std on a later fix");
    // GIVEN a standalone agent at the take-off point
    Agent agent(configFor(Mode::kStandalone));
    StampNs t = kT0;
    auto imuAt = [&](StampNs st) {
      ImuSample s;
      s.stamp_ns = st;
      return agent.onImu(s);
    };
    auto fix = [&](StampNs st, const Vec2& p, double std_m) {
      GnssSample g;
      g.stamp_ns = st;
      g.valid = true;
      g.position_m = p;
      g.std_m = std_m;
      agent.onGnss(g);
    };
    imuAt(t);
    if (!first_fix) {
      fix(t += kMs, Vec2(0.0, 0.0), 0.5);
      imuAt(t += 10 * kMs);
    }
    // WHEN a valid-flagged fix reports std = 1e300 m
    fix(t += kMs, Vec2(0.0, 0.0), 1e300);
    // THEN it is rejected as implausible, once, and nothing else is counted
    expectCounters(agent.diagnostics().rejected, only(&RejectCounters::implausible, 1));
    // AND then good fixes (std 0.5 m) put the UAV 3 m east of the hold point for 5 s
    if (first_fix) fix(t += 50 * kMs, Vec2(0.0, 0.0), 0.5);  // the hold point, if the absurd one was not used
    VelocityCommand last;
    for (int i = 0; i < 500; ++i) {
      last = imuAt(t += 10 * kMs);
      if (i % 10 == 0) fix(t += kMs, Vec2(3.0, 0.0), 0.5);
    }
    expectCounters(agent.diagnostics().rejected, only(&RejectCounters::implausible, 1));
    // AND the estimator's covariance is finite and the good fixes were used: the estimate is near +3 m and the
    // command points west, back to the hold point
    const Diagnostics& d = agent.diagnostics();
    EXPECT_TRUE(allFinite(d.position_cov_m2)) << d.position_cov_m2;
    EXPECT_TRUE(allFinite(d.velocity_cov_m2ps2)) << d.velocity_cov_m2ps2;
    EXPECT_TRUE(allFinite(d.position_m));
    EXPECT_GT(d.position_m.x(), 1.0) << "good fixes after the absurd one were ignored";
    EXPECT_LT(last.velocity_mps.x(), -0.1) << "standalone agent does not steer back to its hold point";
  }
}

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
    static const double garbage[] = {kNan, -kNan, kInf, -kInf, 1e300, -1e300, std::numeric_limits<double>::max(),
                                     std::numeric_limits<double>::denorm_min(), -0.0, 1e-300};
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

struct FuzzOracle {
  bool seen[3] = {false, false, false};
  StampNs last[3] = {0, 0, 0};
  bool have_heading = false;

  bool acceptStamp(int stream, StampNs st) {
    if (seen[stream] && st <= last[stream]) return false;
    seen[stream] = true;
    last[stream] = st;
    return true;
  }
};

bool finiteDiagnostics(const Diagnostics& d) {
  return d.position_m.allFinite() && d.velocity_mps.allFinite() && d.position_cov_m2.allFinite() &&
         d.velocity_cov_m2ps2.allFinite() && d.frame_centre_m.allFinite();
}

bool finiteTracks(const TrackBank& bank) {
  for (const Track& t : bank.tracks())
    if (!t.estimate.x.allFinite() || !t.estimate.P.allFinite()) return false;
  return true;
}

// Everything a fuzz run observed; filled without gtest macros so the run can also execute in a forked child.
struct FuzzResult {
  std::uint64_t inputs = 0;
  std::uint64_t clean_inputs = 0;  // inputs with nothing to reject
  std::uint64_t moving_commands = 0;  // commands with |v| > 0.1 m/s: the agent was really steering
  std::uint64_t bad = 0;    // inputs the spec certainly rejects
  std::uint64_t maybe = 0;  // inputs the spec leaves open (absurd but SPD detection covariance)
  RejectCounters generated;  // certainly-bad inputs by the category the generator gave them
  RejectCounters rejected;   // the agent's counters at the end
  int bad_commands = 0;      // non-finite or above v_max + 1e-12
  int nonfinite_diagnostics = 0;
  int nonfinite_tracks = 0;
  int wrong_bookkeeping = 0;  // seq / answered stamp / commands counter
  int miscounted = 0;         // inputs after which the counters did not move by the expected amount
  std::vector<std::string> first_failures;
};

FuzzResult runFuzz(Mode mode, std::uint64_t seed, int samples) {
  const AgentConfig config = configFor(mode);
  Agent agent(config);
  Fuzzer fz(seed, config.limits);
  FuzzOracle oracle;
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
      const bool finite = std::isfinite(s.roll_rad) && std::isfinite(s.pitch_rad) && std::isfinite(s.heading_rad);
      const bool tilt_ok = std::abs(s.roll_rad) <= lim.max_tilt_rad && std::abs(s.pitch_rad) <= lim.max_tilt_rad;
      if (!finite) {
        ++res.bad, ++res.generated.nonfinite;
      } else if (!tilt_ok) {
        ++res.bad, ++res.generated.implausible;
      } else if (!oracle.acceptStamp(0, s.stamp_ns)) {
        ++res.bad, ++res.generated.out_of_order;
      } else {
        oracle.have_heading = true;
      }
      what = "IMU stamp " + std::to_string(s.stamp_ns) + " roll " + std::to_string(s.roll_rad) + " pitch " +
             std::to_string(s.pitch_rad) + " heading " + std::to_string(s.heading_rad);
      const VelocityCommand c = agent.onImu(s);
      ++imu_count;
      if (!c.velocity_mps.allFinite() || !(c.velocity_mps.norm() <= v_max + 1e-12)) {
        report(res.bad_commands, "input " + std::to_string(n) + ": command (" + std::to_string(c.velocity_mps.x()) +
                                     ", " + std::to_string(c.velocity_mps.y()) + ") not finite or above v_max");
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
          static const Vec2 garbage[] = {Vec2(kNan, 0.0),   Vec2(0.0, kInf),        Vec2(-kInf, kNan),
                                         Vec2(1e300, 0.0),  Vec2(0.0, -1e300),      Vec2(1e6 + 1.0, 0.0),
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
          static const Mat2 bad_cov[] = {mat(kNan, 0.0, 0.0, 0.1),  mat(0.1, kInf, kInf, 0.1),
                                         mat(-0.1, 0.0, 0.0, 0.1),  mat(0.1, 0.05, -0.05, 0.1),
                                         mat(0.1, 0.5, 0.5, 0.1),   Mat2::Zero()};
          static const Mat2 odd_cov[] = {Mat2::Identity() * 1e300, Mat2::Identity() * 1e-100,
                                         mat(1e-6, 0.0, 0.0, 1e6)};
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
      } else if (!oracle.acceptStamp(1, set.stamp_ns)) {
        ++res.bad, ++res.generated.out_of_order;
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
      } else if (!oracle.acceptStamp(2, g.stamp_ns)) {
        ++res.bad, ++res.generated.out_of_order;
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
      report(res.miscounted, "input " + std::to_string(n) + " (" + what + "): counters moved by " +
                                 std::to_string(delta) + ", expected " + std::to_string(res.bad - bad_before) +
                                 (res.maybe > maybe_before ? " (+ up to " + std::to_string(res.maybe - maybe_before) + ")" : ""));
    }
    if (res.bad == bad_before && res.maybe == maybe_before) ++res.clean_inputs;
    rejected_before = d.rejected.total();
    bad_before = res.bad;
    maybe_before = res.maybe;
    if (!finiteDiagnostics(d)) {
      report(res.nonfinite_diagnostics,
             "input " + std::to_string(n) + ": non-finite diagnostics estimate, position (" +
                 std::to_string(d.position_m.x()) + ", " + std::to_string(d.position_m.y()) + ") P00 " +
                 std::to_string(d.position_cov_m2(0, 0)));
    }
    if (!finiteTracks(agent.bank())) report(res.nonfinite_tracks, "input " + std::to_string(n) + ": non-finite track");
    if (d.commands != imu_count) report(res.wrong_bookkeeping, "commands counter != IMU samples");
  }
  res.rejected = agent.diagnostics().rejected;
  return res;
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

constexpr unsigned kDeadlineS = 10;  // a clean run takes about 0.1 s

TEST(AgentInputFuzz, CommandsFiniteAndSaturatedAndCountersMatchInEveryMode) {
  for (const Mode mode : {Mode::kSwa, Mode::kStandalone, Mode::kAnchored}) {
    for (const std::uint64_t seed : {11u, 12u}) {
      SCOPED_TRACE("mode " + toString(mode) + " seed " + std::to_string(seed));
      constexpr int kSamples = 20'000;
      // GIVEN a seeded stream of 2e4 random IMU, detection and GNSS samples mixing valid values, NaN, +-inf, 1e300,
      // DBL_MAX, huge and negative IDs, repeated / backward / far-jumping stamps and oversized sets
      // WHEN an agent consumes it (first in a child process: an agent that hangs must fail, not stall the suite)
      const std::string hang = runWithDeadline(kDeadlineS, [&] { runFuzz(mode, seed, kSamples); });
      EXPECT_EQ(hang, "") << "agent did not get through the fuzz stream";
      if (!hang.empty()) continue;
      const FuzzResult r = runFuzz(mode, seed, kSamples);

      // THEN every command is finite and within saturation, the estimate and the tracks stay finite
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
                         &RejectCounters::bad_id, &RejectCounters::implausible, &RejectCounters::no_heading}) {
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

// The assignment cost of an anonymous detection is mahalanobis2 + ln det S. A detection covariance of 1e300 m^2
// passes isCovariance() (its determinant overflows to +inf, and inf > 0), so ln det S = +inf reaches the Hungarian
// solver, whose potentials become inf - inf = NaN and whose augmenting search never terminates.
TEST(AgentInputDetections, AnonymousDetectionWithAbsurdCovarianceDoesNotHangTheAgent) {
  for (const double variance : {1e155, 1e300}) {
    std::ostringstream label;
    label << "variance " << variance << " m^2";
    SCOPED_TRACE(label.str());
    // GIVEN an agent with one tentative anonymous track 5 m ahead
    auto scenario = [variance](Agent& agent) {
      ImuSample imu;
      imu.stamp_ns = kT0;
      agent.onImu(imu);
      DetectionSet set;
      set.stamp_ns = kT0 + kMs;
      set.detections = {det(kAnonymousId, 5.0, 0.0)};
      agent.onDetections(set);
      // WHEN an anonymous detection at the same place arrives with covariance variance * I (finite, SPD)
      set.stamp_ns += 100 * kMs;
      set.detections = {det(kAnonymousId, 5.0, 0.0, Mat2(Mat2::Identity() * variance))};
      agent.onDetections(set);
      // AND then an ordinary one
      set.stamp_ns += 100 * kMs;
      set.detections = {det(kAnonymousId, 5.0, 0.0)};
      agent.onDetections(set);
    };
    // THEN the agent returns (checked in a child process with a deadline)
    const std::string hang = runWithDeadline(5, [&] {
      Agent agent(configFor(Mode::kSwa));
      scenario(agent);
    });
    EXPECT_EQ(hang, "");
    if (!hang.empty()) continue;
    // AND the detection was either rejected as implausible or used harmlessly: tracks finite, nothing else counted
    Agent agent(configFor(Mode::kSwa));
    scenario(agent);
    const RejectCounters& r = agent.diagnostics().rejected;
    EXPECT_EQ(r.total(), r.implausible);
    EXPECT_LE(r.implausible, 1u);
    EXPECT_TRUE(finiteTracks(agent.bank()));
    EXPECT_FALSE(agent.bank().tracks().empty());
  }
}

// ===============================================================================================================
// Stamps far apart

// secondsBetween(from, to) computes `to - from` in int64: two accepted stamps more than INT64_MAX ns apart (e.g. a
// first sample stamped near INT64_MIN, then one near INT64_MAX) overflow, which is undefined behaviour (UBSan aborts
// here) and in practice wraps to a tiny negative interval. The agent must treat them as what they are: far apart.
TEST(AgentInputStamps, StampsMoreThanInt64MaxApartDoNotOverflow) {
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
    // WHEN the next samples are stamped near INT64_MAX (strictly later: nothing is out of order), the detection set
    // seeing only neighbour 2
    imu.stamp_ns = hi - 10;
    const VelocityCommand c = agent.onImu(imu);
    set.stamp_ns = hi - 5;
    set.detections = {det(2, 0.0, 5.0)};
    agent.onDetections(set);
    g.stamp_ns = hi - 3;
    agent.onGnss(g);
    imu.stamp_ns = hi;
    const VelocityCommand d = agent.onImu(imu);
    // THEN nothing is rejected, commands are finite and saturated, and neighbour 1, silent for ~585 years, is gone
    expectCounters(agent.diagnostics().rejected, RejectCounters{});
    for (const VelocityCommand& v : {c, d}) {
      EXPECT_TRUE(allFinite(v.velocity_mps));
      EXPECT_LE(v.velocity_mps.norm(), agent.config().control.v_max_mps + 1e-12);
    }
    EXPECT_TRUE(finiteDiagnostics(agent.diagnostics()));
    EXPECT_EQ(agent.bank().find(1), nullptr) << "a track last seen ~585 years ago was not pruned (interval wrapped)";
    EXPECT_NE(agent.bank().find(2), nullptr);
  }
}

// ===============================================================================================================
// Determinism

TEST(AgentDeterminism, SameStreamGivesBitIdenticalCommandsAndPerturbationIsVisible) {
  // GIVEN 60 s of realistic samples: 8 identified neighbours hovering on a ring of r = 10 m (0.05 m detection
  // noise), IMU 100 Hz with tilt and heading noise, detections and GNSS at 10 Hz
  Scene scene = ringScene(8, 10.0, Vec2(2.0, -1.0));
  scene.det_noise_m = 0.05;
  scene.tilt_noise_rad = 0.02;
  scene.heading_noise_rad = 0.003;
  scene.gnss_noise_m = 0.5;
  const std::vector<Event> stream = makeStream(scene, kT0, 60 * kSec, 2024);

  // The third agent's stream differs by 1e-9 m in one input at t = 20 s: a detection of neighbour 4 (one of the
  // three nearest) or, in standalone mode where detections do not steer, a GNSS fix.
  auto perturbed = [&](Mode mode) {
    std::vector<Event> s = stream;
    for (Event& e : s) {
      if (mode != Mode::kStandalone && e.kind == Event::Kind::kDetections && e.detections.stamp_ns > kT0 + 20 * kSec) {
        for (Detection& d : e.detections.detections)
          if (d.target_id == 4) d.position_body_m.x() += 1e-9;
        break;
      }
      if (mode == Mode::kStandalone && e.kind == Event::Kind::kGnss && e.gnss.stamp_ns > kT0 + 20 * kSec) {
        e.gnss.position_m.x() += 1e-9;
        break;
      }
    }
    return s;
  };

  for (const Mode mode : {Mode::kSwa, Mode::kStandalone, Mode::kAnchored}) {
    SCOPED_TRACE("mode " + toString(mode));
    Agent a(configFor(mode)), b(configFor(mode)), c(configFor(mode));
    // WHEN two agents get the same stream and a third the perturbed one
    const std::vector<VelocityCommand> ca = feedAll(a, stream);
    const std::vector<VelocityCommand> cb = feedAll(b, stream);
    const std::vector<VelocityCommand> cc = feedAll(c, perturbed(mode));

    // THEN the first two give bit-identical command sequences
    ASSERT_EQ(ca.size(), 6000u);
    ASSERT_EQ(cb.size(), ca.size());
    std::size_t first_mismatch = ca.size();
    for (std::size_t i = 0; i < ca.size() && first_mismatch == ca.size(); ++i)
      if (!sameCommand(ca[i], cb[i])) first_mismatch = i;
    EXPECT_EQ(first_mismatch, ca.size()) << "commands differ from index " << first_mismatch;
    // AND identical final diagnostics and state
    expectSameState(a, b, /*with_counters=*/true, /*with_commands=*/true);
    // AND the stream was clean and exercised the agent: tracking, non-trivial commands
    expectCounters(a.diagnostics().rejected, RejectCounters{});
    EXPECT_EQ(a.diagnostics().stage, Stage::kTracking);
    double max_norm = 0.0;
    for (const VelocityCommand& v : ca) max_norm = std::max(max_norm, v.velocity_mps.norm());
    EXPECT_GT(max_norm, 0.1);

    // AND the perturbed stream gives a different command sequence (the comparison is sensitive), identical before
    // the perturbation
    ASSERT_EQ(cc.size(), ca.size());
    std::size_t first_diff = ca.size();
    for (std::size_t i = 0; i < ca.size() && first_diff == ca.size(); ++i)
      if (!sameBits(ca[i].velocity_mps, cc[i].velocity_mps)) first_diff = i;
    EXPECT_LT(first_diff, ca.size()) << "a 1e-9 m perturbation did not change any command";
    if (first_diff < ca.size()) {
      EXPECT_GT(ca[first_diff].stamp_ns, kT0 + 20 * kSec);
    }
  }
}

// ===============================================================================================================
// Saturation

TEST(AgentSaturation, FarNeighbourGivesCommandsOfExactlyVmaxTowardsTheFrame) {
  // GIVEN one neighbour 39 m away (inside sensing_range_m = 40) at 0.7 rad in the stable frame, heading 0.4 rad: the
  // floating frame is r = 10 m short of it, ~29 m from self, far beyond what k_p (0.5/s) can cover at v_max = 2 m/s
  const AgentConfig config = configFor(Mode::kSwa);
  ASSERT_GT(config.formation.sensing_range_m, 39.0);
  const Vec2 dir(std::cos(0.7), std::sin(0.7));
  Scene scene;
  scene.neighbours = {{5, 39.0 * dir}};
  scene.heading_rad = 0.4;
  scene.gnss = false;
  const std::vector<Event> stream = makeStream(scene, kT0, 10 * kSec, 1);

  // WHEN the agent runs on it for 10 s
  Agent agent(config);
  int saturated = 0;
  for (const Event& e : stream) {
    const auto c = feed(agent, e);
    if (!c) continue;
    const Diagnostics& d = agent.diagnostics();
    const double n = c->velocity_mps.norm();
    // THEN every command is finite and within saturation
    ASSERT_TRUE(allFinite(c->velocity_mps));
    ASSERT_LE(n, config.control.v_max_mps + 1e-12);
    if (d.stage != Stage::kTracking) {
      EXPECT_TRUE(sameBits(c->velocity_mps, Vec2::Zero())) << "no frame yet: hover";
      continue;
    }
    // AND once tracking, the frame is 29 m towards the neighbour and the command has norm v_max, pointing at it
    EXPECT_TRUE(d.frame_valid);
    EXPECT_NEAR((d.frame_centre_m - 29.0 * dir).norm(), 0.0, 1e-9) << d.frame_centre_m.transpose();
    EXPECT_NEAR(n, config.control.v_max_mps, 1e-12);
    const Vec2 u = c->velocity_mps / n;
    EXPECT_NEAR(u.x() * dir.y() - u.y() * dir.x(), 0.0, 1e-9) << "command not along the frame direction";
    EXPECT_GT(u.dot(dir), 0.0) << "command points away from the frame";
    ++saturated;
  }
  EXPECT_GT(saturated, 900);
  expectCounters(agent.diagnostics().rejected, RejectCounters{});
}

TEST(AgentSaturation, NeighboursBeyondSensingRangeGiveHover) {
  // GIVEN neighbours 1000 m and 41 m away in one direction (outside sensing_range_m = 40)
  Scene scene;
  const Vec2 dir(std::cos(-2.0), std::sin(-2.0));
  scene.neighbours = {{1, 1000.0 * dir}, {2, 1000.0 * dir + Vec2(10.0, 0.0)}, {3, 41.0 * dir}};
  scene.gnss = false;
  const std::vector<Event> stream = makeStream(scene, kT0, 5 * kSec, 1);
  // WHEN the agent runs on them
  Agent agent(configFor(Mode::kSwa));
  const std::vector<VelocityCommand> commands = feedAll(agent, stream);
  // THEN they are tracked but are not neighbours: no frame, every command is exactly zero
  EXPECT_EQ(agent.diagnostics().confirmed_tracks, 3);
  EXPECT_EQ(agent.diagnostics().neighbour_count, 0);
  EXPECT_FALSE(agent.diagnostics().frame_valid);
  for (const VelocityCommand& c : commands) ASSERT_TRUE(sameBits(c.velocity_mps, Vec2::Zero()));
  expectCounters(agent.diagnostics().rejected, RejectCounters{});
}

TEST(AgentSaturation, FarGnssFixesSaturateStandaloneAndAnchoredCommands) {
  for (const Mode mode : {Mode::kStandalone, Mode::kAnchored}) {
    SCOPED_TRACE("mode " + toString(mode));
    // GIVEN a hold point at the origin and then fixes 500 km away
    AgentConfig config = configFor(mode);
    Agent agent(config);
    StampNs t = kT0;
    ImuSample imu;
    imu.stamp_ns = t;
    agent.onImu(imu);
    GnssSample g;
    g.valid = true;
    g.std_m = 0.5;
    g.stamp_ns = t += kMs;
    agent.onGnss(g);
    g.position_m = Vec2(3e5, -4e5);
    // WHEN the agent runs for 3 s
    for (int i = 0; i < 300; ++i) {
      imu.stamp_ns = t += 10 * kMs;
      const VelocityCommand c = agent.onImu(imu);
      if (i % 10 == 0) {
        g.stamp_ns = t += kMs;
        agent.onGnss(g);
      }
      // THEN every command is finite and within saturation
      ASSERT_TRUE(allFinite(c.velocity_mps));
      ASSERT_LE(c.velocity_mps.norm(), config.control.v_max_mps + 1e-12);
      if (i > 50) {
        EXPECT_NEAR(c.velocity_mps.norm(), config.control.v_max_mps, 1e-12);
      }
    }
    expectCounters(agent.diagnostics().rejected, RejectCounters{});
  }
}

}  // namespace
}  // namespace swa::agent

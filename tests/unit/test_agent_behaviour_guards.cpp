// Behaviour guards at the Agent facade: the agent is deterministic, bit for bit (and a tiny perturbation is
// visible), and commands saturate at exactly v_max towards far targets, or hover when nothing is in sensing range.
// Shared helpers: agent_input_support.h.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include <gtest/gtest.h>

#include "agent_input_support.h"
#include "swa/agent/agent.h"

namespace swa::agent {
namespace {

using namespace testing;  // agent_input_support.h

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
  // floating frame is r = 10 m short of it, ~29 m from self, far beyond what k_p (0.7/s) can cover at v_max = 2 m/s
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

// The anchored hold after a GNSS outage (issue #43): blended back in over anchor.regain_ramp_s, not switched on as a
// step; with 0, at once.
std::vector<Vec2> anchoredAcrossAnOutage(double ramp_s) {
  AgentConfig config = configFor(Mode::kAnchored);
  config.anchor.regain_ramp_s = ramp_s;
  Agent agent(config);
  StampNs t = kT0;
  ImuSample imu;
  GnssSample g;
  g.std_m = 0.5;
  std::vector<Vec2> commands;
  // GIVEN a hold point at the origin (2 s of fixes there), an outage of 5 s, then fixes 3 m east: the UAV drifted
  for (int i = 0; i < 1'000; ++i) {
    imu.stamp_ns = t += 10 * kMs;
    commands.push_back(agent.onImu(imu).velocity_mps);
    if (i % 10 == 0) {
      g.stamp_ns = t += kMs;
      g.valid = i < 200 || i >= 700;
      g.position_m = i < 200 ? Vec2::Zero() : Vec2(3.0, 0.0);
      agent.onGnss(g);
    }
  }
  expectCounters(agent.diagnostics().rejected, RejectCounters{});
  return commands;
}

TEST(AgentAnchor, AfterAGnssOutageTheHoldIsBlendedInOverRegainRampNotSwitchedOnAtOnce) {
  const std::vector<Vec2> at_once = anchoredAcrossAnOutage(0.0), ramped = anchoredAcrossAnOutage(2.0);
  // THEN without the ramp the pull back west is there in the first IMU period after the fix: a step
  const Vec2 pull = at_once.back();
  ASSERT_LT(pull.x(), -0.05);
  EXPECT_TRUE(at_once[699].isZero());
  EXPECT_GT((at_once[701] - at_once[700]).norm(), 0.5 * pull.norm());
  // AND with it no IMU period changes the command by a twentieth of that pull (the fixes, at 10 Hz, still move the
  // estimate it pulls from), and 3 s after the fix the pull is within 5 % of the same (the estimator, predicted with
  // the commands sent, is not quite where the other one is)
  double largest = 0.0;
  for (std::size_t k = 1; k < ramped.size(); ++k) largest = std::max(largest, (ramped[k] - ramped[k - 1]).norm());
  EXPECT_LE(largest, 0.05 * pull.norm());
  EXPECT_LE((ramped.back() - pull).norm(), 0.05 * pull.norm());
  // AND the first fix of the flight is no return: the hold is on from it, as before the ramp existed
  EXPECT_EQ(ramped[100], at_once[100]);
}

}  // namespace
}  // namespace swa::agent

#include <algorithm>
#include <cmath>
#include <iostream>

#include <gtest/gtest.h>

#include "focal_scenario.h"
#include "swa/agent/focal_estimator.h"
#include "swa/agent/frame_fit.h"
#include "swa/agent/imu_bias.h"
#include "swa/agent/neighbourhood.h"
#include "swa/agent/track_bank.h"
#include "swa/monitor/chi2.h"

namespace swa::agent {
namespace {

using testing::FocalWorld;

struct AneesSeries {
  std::vector<double> position, velocity;  // per time step, averaged over the runs
};

// The estimation chain of one agent (bank -> neighbours -> frame -> focal filter, IMU-bias removal on the tilt
// acceleration), driven by a trajectory-tracking command instead of the formation controller, as in the paper's
// tuning experiment: the focal UAV flies a figure of eight relative to a hovering group of three, so its estimate is
// exercised while it manoeuvres. The frame is always fitted on all three (k nearest, k = 3): the chain has no
// handling of neighbour-set changes (Agent::updateFrame has), and Gabriel's rule would drop the far one of the group
// whenever the UAV comes close to another. The three sit on one r-circle, so the fit weights do not move the frame.
AneesSeries runMonteCarlo(AgentConfig cfg, int runs, double duration_s, double warmup_s) {
  cfg.formation.neighbourhood = NeighbourhoodRule::kKNearest;
  cfg.formation.k = 3;
  const double dt = 0.01;
  const int steps = static_cast<int>(duration_s / dt);
  const int first = static_cast<int>(warmup_s / dt);
  AneesSeries out;
  out.position.assign(steps - first, 0.0);
  out.velocity.assign(steps - first, 0.0);
  std::vector<Vec2> group;
  for (double deg : {90.0, 210.0, 330.0})
    group.push_back(10.0 * Vec2(std::cos(deg * M_PI / 180), std::sin(deg * M_PI / 180)));
  const Mat2 R_pos = Mat2::Identity() * cfg.focal.r_pos_m2;
  const Mat2 R_acc = Mat2::Identity() * cfg.focal.r_acc_m2ps4;

  for (int run = 0; run < runs; ++run) {
    FocalWorld world(1000 + static_cast<std::uint64_t>(run), group, Vec2(1.0, -1.0), FocalWorld::Options{});
    TrackBank bank(cfg.surroundings);
    FocalEstimator focal(cfg.focal);
    ImuBiasRemover bias(cfg.focal.bias_window_s, cfg.focal.bias_freeze_speed_mps, cfg.focal.bias_freeze_hold_s);
    std::vector<StableDetection> stable;
    Vec2 u = Vec2::Zero();
    const double phase = 0.7 * run;
    for (int k = 0; k < steps; ++k) {
      const StampNs t = static_cast<StampNs>(k) * 10'000'000;
      const double time = k * dt;
      world.step(dt, u);

      if (k % 10 == 0) {
        const DetectionSet set = world.detections(t);
        stable.clear();
        const Mat2 R = rotation(world.opt.heading_rad);
        for (const Detection& d : set.detections)
          stable.push_back({d.target_id, R * d.position_body_m, Mat2::Identity() * cfg.surroundings.r_det_m2});
        bank.update(t, stable);
        const Neighbourhood nb = selectNeighbours(bank.tracks(), cfg.formation);
        const FrameFit fit = fitFloatingFrame(nb.positions, cfg.formation.radius_m, cfg.formation.circle_fit,
                                              cfg.formation.far_neighbour_weight);
        if (fit.valid) {
          if (!focal.initialized()) {
            focal.initialize(t, -fit.centre, R_pos);
            bias.reset();
          } else {
            focal.predictTo(t, u);
            focal.correctPosition(-fit.centre, R_pos);
          }
        }
      }
      const ImuSample imu = world.imu(t);
      const Vec2 acc_body = bias.correct(cfg.focal.q_c_mps2 * Vec2(imu.pitch_rad, imu.roll_rad), t, u);
      const Vec2 acc = rotation(imu.heading_rad) * acc_body;
      focal.predictTo(t, u);
      focal.correctAcceleration(acc, R_acc);

      // Trajectory: a figure of eight of 4 m x 2 m around the group centre, period ~31 s, tracked on the estimate.
      const double w = 0.2;
      const Vec2 ref(4.0 * std::sin(w * time + phase), 2.0 * std::sin(2 * w * time + phase));
      const Vec2 ref_v(4.0 * w * std::cos(w * time + phase), 4.0 * w * std::cos(2 * w * time + phase));
      u = focal.initialized() ? Vec2(ref_v + 0.5 * (ref - focal.position()) - 0.3 * focal.velocity()) : Vec2::Zero();

      if (k < first || !focal.initialized()) continue;
      // Truth in the floating frame: the same fit on the true neighbour positions relative to the UAV.
      NeighbourPositions truth;
      for (const Vec2& g : group) truth.position[truth.count++] = g - world.p;
      std::sort(truth.position.begin(), truth.position.begin() + truth.count,
                [](const Vec2& a, const Vec2& b) { return a.squaredNorm() < b.squaredNorm(); });
      const FrameFit true_fit =
          fitFloatingFrame(truth, cfg.formation.radius_m, cfg.formation.circle_fit, cfg.formation.far_neighbour_weight);
      const Vec2 e_p = focal.position() - (-true_fit.centre);
      const Vec2 e_v = focal.velocity() - world.v;  // the group hovers: frame velocity is zero
      out.position[k - first] += e_p.dot(focal.positionCov().ldlt().solve(e_p)) / runs;
      out.velocity[k - first] += e_v.dot(focal.velocityCov().ldlt().solve(e_v)) / runs;
    }
  }
  return out;
}

double mean(const std::vector<double>& v) {
  double s = 0.0;
  for (double x : v) s += x;
  return s / static_cast<double>(v.size());
}

double fractionInside(const std::vector<double>& v, const monitor::AneesBand& band) {
  const auto n = std::count_if(v.begin(), v.end(), [&](double x) { return x >= band.low && x <= band.high; });
  return static_cast<double>(n) / static_cast<double>(v.size());
}

TEST(FocalConsistency, AneesOfPositionAndVelocityIsInsideTheChi2BandWithDefaults) {
  // GIVEN K = 24 seeded runs of 60 s of the §IV-C scenario with the default (tuned) configuration
  constexpr int kRuns = 24;
  const AgentConfig cfg;
  const monitor::AneesBand band = monitor::aneesBand(kRuns, 2);
  // WHEN the ANEES of position and velocity is computed per 10 ms step after a 5 s warm-up
  const AneesSeries s = runMonteCarlo(cfg, kRuns, 60.0, 5.0);
  const double p_mean = mean(s.position), v_mean = mean(s.velocity);
  const double p_in = fractionInside(s.position, band), v_in = fractionInside(s.velocity, band);
  std::cout << "band [" << band.low << ", " << band.high << "]  ANEES position mean " << p_mean << " inside " << p_in
            << "  velocity mean " << v_mean << " inside " << v_in << "\n";
  // THEN both time-averaged ANEES lie in the 95 % band, and the per-step ANEES is inside it at least 85 % of the
  // time. A filter whose errors were exactly Gaussian with covariance P would score 95 %; ours carries unmodelled
  // effects (constant IMU bias per run, the 1 s velocity lag of the vehicle versus the paper's damped model,
  // time-correlated frame noise from the smoothed tracks) that fatten the NEES tails. Measured: ~90 %.
  EXPECT_GE(p_mean, band.low);
  EXPECT_LE(p_mean, band.high);
  EXPECT_GE(v_mean, band.low);
  EXPECT_LE(v_mean, band.high);
  EXPECT_GE(p_in, 0.85);
  EXPECT_GE(v_in, 0.85);
}

TEST(FocalConsistency, PaperQfAsWrittenIsConservative) {
  // GIVEN the same scenario with Table I's Q_f unscaled
  constexpr int kRuns = 24;
  AgentConfig cfg;
  cfg.focal.q_pos_m2 = 5e-2;
  cfg.focal.q_vel_m2ps2 = 5e-1;
  cfg.focal.q_acc_m2ps4 = 5.0;
  cfg.focal.r_pos_m2 = 0.02;
  const monitor::AneesBand band = monitor::aneesBand(kRuns, 2);
  // WHEN evaluated
  const AneesSeries s = runMonteCarlo(cfg, kRuns, 60.0, 5.0);
  std::cout << "paper Q_f: ANEES position mean " << mean(s.position) << " velocity mean " << mean(s.velocity) << "\n";
  // THEN the filter overstates its uncertainty: both ANEES fall below the band, which is why the defaults differ
  // from Table I (DESIGN §3.4)
  EXPECT_LT(mean(s.position), band.low);
  EXPECT_LT(mean(s.velocity), band.low);
}

}  // namespace
}  // namespace swa::agent

// Agent's floating frame: which neighbours define it, the circle fit through them and how much the fit is trusted.
// Apart from agent.cpp because keeping the focal estimate continuous across frame changes is a job of its own.
#include "swa/agent/agent.h"

#include "swa/agent/frame_fit.h"
#include "swa/agent/geometry.h"
#include "swa/agent/neighbourhood.h"
#include "swa/agent/samples.h"

namespace swa::agent {
namespace {

// Bounds of the propagated R_c (fitNoise): 1e-6 m^2 is far below any relative-localisation accuracy, 1e4 m^2 makes
// a fit worthless to the filter without putting its arithmetic near overflow.
constexpr double kMinFitVarianceM2 = 1e-6;
constexpr double kMaxFitVarianceM2 = 1e4;

}  // namespace

void Agent::updateFrame(StampNs stamp) {
  const FormationConfig& fc = config_.formation;
  const Neighbourhood next = selectNeighbours(bank_.tracks(), fc);
  const FrameFit now = fit(next.positions);
  fit_case_ = now.fit_case;
  if (!now.valid) {
    frame_valid_ = false;
    neighbours_ = next;
    return;
  }
  const Vec2 z = -now.centre;  // z_p = -r_c: own position in the floating frame
  const Mat2 r_fit = fitNoise(next, now);
  focal_.predictTo(stamp, relativeCommand());
  const bool stale = secondsBetween(last_frame_ns_, stamp) > config_.focal.frame_timeout_s;
  if (!focal_.initialized()) {
    focal_.initialize(stamp, z, r_fit);
    imu_bias_.reset();
  } else if (stale) {
    focal_.resetPosition(z, r_fit);
    ++diag_.frame_resets;
  } else if (!next.sameFrameAs(neighbours_, rankedFit())) {
    // The frame jumps when the neighbour set changes (or, with the weighted fit, which two are the nearest). Where the
    // old neighbours are all still tracked, evaluate the old frame now and move the estimate by the jump, so the filter
    // never sees it as an innovation; otherwise restart the position from this measurement.
    NeighbourPositions old;
    FrameFit old_fit;
    if (frame_valid_ && positionsOf(bank_.tracks(), neighbours_, old)) {
      old_fit = fit(old);
    }
    if (old_fit.valid) {
      focal_.shiftFrame(now.centre - old_fit.centre);
      focal_.correctPosition(z, r_fit);
      ++diag_.frame_shifts;
    } else {
      focal_.resetPosition(z, r_fit);
      ++diag_.frame_resets;
    }
  } else {
    focal_.correctPosition(z, r_fit);
  }
  neighbours_ = next;
  frame_valid_ = true;
  frame_centre_ = now.centre;
  last_frame_ns_ = stamp;
}

Mat2 Agent::fitNoise(const Neighbourhood& neighbours, const FrameFit& fit) const {
  const double gain = config_.focal.fit_noise_gain;
  Mat2 cov;
  if (gain <= 0.0 || !fitCovariance(neighbours.positions, neighbours.covariances, fit, config_.formation.radius_m,
                                    config_.formation.far_neighbour_weight, cov)) {
    return r_pos_;
  }
  Mat2 r = gain * cov;
  // A tiny floor keeps R positive definite where the fit does not depend on a direction at all (n = 1: the
  // tangent), and a ceiling keeps it finite where it is nearly undetermined (two neighbours in line with the
  // centre): such a fit then weighs next to nothing.
  r.diagonal().array() += kMinFitVarianceM2;
  if (!isCovariance(r) || r.trace() > kMaxFitVarianceM2) return Mat2::Identity() * kMaxFitVarianceM2;
  return r;
}

bool Agent::rankedFit() const {
  const FormationConfig& fc = config_.formation;
  return fc.circle_fit == CircleFit::kFixedRadius && fc.far_neighbour_weight != 1.0;
}

FrameFit Agent::fit(const NeighbourPositions& neighbours) const {
  const FormationConfig& fc = config_.formation;
  return fitFloatingFrame(neighbours, fc.radius_m, fc.circle_fit, fc.far_neighbour_weight);
}

}  // namespace swa::agent

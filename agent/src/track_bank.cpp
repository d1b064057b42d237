#include "swa/agent/track_bank.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace swa::agent {
namespace {

// Chi-square quantile with 2 degrees of freedom has a closed form: -2 ln(1 - p).
double chi2Quantile2Dof(double p) { return -2.0 * std::log1p(-p); }

constexpr double kReinitGateProbability = 1.0 - 1e-6;
constexpr double kForbiddenCost = 1e9;

}  // namespace

TrackBank::TrackBank(const SurroundingsConfig& config)
    : config_(config),
      noise_{config.q_pos_m2, config.q_vel_m2ps2, config.q_acc_m2ps4, config.q_ref_dt_s},
      gate_(chi2Quantile2Dof(config.gate_probability)),
      reinit_gate_(chi2Quantile2Dof(kReinitGateProbability)) {
  tracks_.reserve(kMaxTracks);
}

const Track* TrackBank::find(int id) const {
  for (const Track& t : tracks_)
    if (t.id == id) return &t;
  return nullptr;
}

int TrackBank::confirmedCount() const {
  return static_cast<int>(std::count_if(tracks_.begin(), tracks_.end(), [](const Track& t) { return t.confirmed; }));
}

int TrackBank::tentativeCount() const { return static_cast<int>(tracks_.size()) - confirmedCount(); }

void TrackBank::predict(Track& track, StampNs stamp) {
  const double dt = secondsBetween(track.time_ns, stamp);
  if (dt <= 0.0) return;
  // All tracks usually share one step (the MPS period): build F and Q once per distinct dt.
  if (dt != cached_dt_) {
    F_ = pvaTransition(dt);
    Q_ = pvaProcessNoise(noise_, dt);
    cached_dt_ = dt;
  }
  Pva::predict(track.estimate, F_, Q_);
  track.time_ns = stamp;
}

bool TrackBank::correct(Track& track, const StableDetection& det, StampNs stamp) {
  const Innovation<2> in = Pva::innovation<2>(track.estimate, positionObservation(), det.position_m, det.covariance_m2);
  return correct(track, det, in, stamp);
}

bool TrackBank::correct(Track& track, const StableDetection& det, const Innovation<2>& in, StampNs stamp) {
  if (!Pva::correct<2>(track.estimate, positionObservation(), det.covariance_m2, in)) return false;
  track.last_detection_ns = stamp;
  ++track.hits;
  if (track.hits >= config_.confirm_hits) track.confirmed = true;
  return true;
}

int TrackBank::startTrack(const StableDetection& det, StampNs stamp, bool anonymous) {
  if (tracks_.size() >= kMaxTracks) return -1;
  Track t;
  t.id = det.target_id;
  if (anonymous) {
    t.id = next_anonymous_id_;
    // Wraps after ~1.1e9 tracks (years of clutter at 10 Hz); by then every early id is long gone.
    next_anonymous_id_ =
        next_anonymous_id_ == std::numeric_limits<int>::max() ? kFirstAnonymousTrackId : next_anonymous_id_ + 1;
  }
  t.anonymous = anonymous;
  t.created_ns = stamp;
  t.last_detection_ns = stamp;
  t.time_ns = stamp;
  t.hits = 1;
  t.confirmed = t.hits >= config_.confirm_hits;
  t.estimate.x.setZero();
  segment<pva::Pos>(t.estimate.x) = det.position_m;
  t.estimate.P.setZero();
  block<pva::Pos, pva::Pos>(t.estimate.P) = det.covariance_m2;
  block<pva::Vel, pva::Vel>(t.estimate.P) = Mat2::Identity() * config_.init_vel_var_m2ps2;
  block<pva::Acc, pva::Acc>(t.estimate.P) = Mat2::Identity() * config_.init_acc_var_m2ps4;
  tracks_.push_back(t);
  return t.id;
}

void TrackBank::associateAnonymous(const std::vector<StableDetection>& dets, StampNs stamp, BankUpdateStats& stats) {
  free_dets_.clear();
  for (std::size_t j = 0; j < dets.size(); ++j)
    if (dets[j].target_id == kAnonymousId) free_dets_.push_back(static_cast<int>(j));
  if (free_dets_.empty()) return;

  // Confirmed tracks choose first, tentative ones get what is left: otherwise a fresh clutter track, whose broad
  // covariance makes every detection look close in Mahalanobis terms, steals a real neighbour's detections.
  for (const bool confirmed_pass : {true, false}) {
    anon_tracks_.clear();
    for (std::size_t i = 0; i < tracks_.size(); ++i)
      if (tracks_[i].anonymous && tracks_[i].confirmed == confirmed_pass) anon_tracks_.push_back(static_cast<int>(i));
    assignPass(dets, stamp, stats);
  }
  for (const int j : free_dets_) {
    const int id = startTrack(dets[j], stamp, true);
    if (id < 0) {
      ++stats.dropped_capacity;
    } else {
      ++stats.created;
      last_track_of_detection_[j] = id;
    }
  }
}

void TrackBank::assignPass(const std::vector<StableDetection>& dets, StampNs stamp, BankUpdateStats& stats) {
  const int rows = static_cast<int>(anon_tracks_.size());
  const int cols = static_cast<int>(free_dets_.size());
  if (rows == 0 || cols == 0) return;
  cost_.assign(static_cast<std::size_t>(rows) * cols, kForbiddenCost);
  const auto H = positionObservation();
  for (int r = 0; r < rows; ++r) {
    const Track& t = tracks_[anon_tracks_[r]];
    for (int c = 0; c < cols; ++c) {
      const StableDetection& d = dets[free_dets_[c]];
      const Innovation<2> in = Pva::innovation<2>(t.estimate, H, d.position_m, d.covariance_m2);
      // Gate on the Mahalanobis distance; rank by the negative log-likelihood, which adds ln|S| so a broad track
      // does not win over a tight one just by being uncertain.
      if (in.valid && in.mahalanobis2 <= gate_) {
        const double cost = in.mahalanobis2 + std::log(in.S(0, 0) * in.S(1, 1) - in.S(0, 1) * in.S(1, 0));
        // The assignment's arithmetic must stay finite; a non-finite cost can only come from a broken track.
        if (std::isfinite(cost)) cost_[static_cast<std::size_t>(r) * cols + c] = cost;
      }
    }
  }
  const std::vector<int>& assigned = assignment_.solve(cost_, rows, cols);
  taken_.assign(static_cast<std::size_t>(cols), 0);
  for (int r = 0; r < rows; ++r) {
    const int c = assigned[r];
    if (c < 0 || cost_[static_cast<std::size_t>(r) * cols + c] >= kForbiddenCost) continue;
    Track& t = tracks_[anon_tracks_[r]];
    if (correct(t, dets[free_dets_[c]], stamp)) {
      ++stats.corrected;
      last_track_of_detection_[free_dets_[c]] = t.id;
      taken_[c] = 1;
    }
  }
  int kept = 0;
  for (int c = 0; c < cols; ++c)
    if (!taken_[c]) free_dets_[kept++] = free_dets_[c];
  free_dets_.resize(kept);
}

BankUpdateStats TrackBank::update(StampNs stamp, const std::vector<StableDetection>& dets) {
  BankUpdateStats stats;
  // Prune before predicting: a track silent past its timeout is gone anyway, and predicting it across a long
  // gap would only overflow its covariance.
  stats.removed = prune(stamp);
  for (Track& t : tracks_) predict(t, stamp);
  last_track_of_detection_.assign(dets.size(), -1);

  const auto H = positionObservation();
  for (std::size_t j = 0; j < dets.size(); ++j) {
    const StableDetection& d = dets[j];
    if (d.target_id == kAnonymousId) continue;
    auto it = std::find_if(tracks_.begin(), tracks_.end(),
                           [&](const Track& t) { return !t.anonymous && t.id == d.target_id; });
    if (it == tracks_.end()) {
      const int id = startTrack(d, stamp, false);
      id < 0 ? ++stats.dropped_capacity : ++stats.created;
      last_track_of_detection_[j] = id;
      continue;
    }
    const Innovation<2> in = Pva::innovation<2>(it->estimate, H, d.position_m, d.covariance_m2);
    if (!in.valid || in.mahalanobis2 > reinit_gate_) {
      // The ID is trusted over the track: restart it where the sensor says the neighbour is, keeping its status.
      const bool was_confirmed = it->confirmed;
      const int hits = it->hits;
      const StampNs created = it->created_ns;
      tracks_.erase(it);
      startTrack(d, stamp, false);
      Track& fresh = tracks_.back();
      fresh.confirmed = was_confirmed;
      fresh.hits = hits;
      fresh.created_ns = created;
      ++stats.reinitialised;
      last_track_of_detection_[j] = fresh.id;
      continue;
    }
    if (correct(*it, d, in, stamp)) {
      ++stats.corrected;
      last_track_of_detection_[j] = it->id;
    }
  }
  associateAnonymous(dets, stamp, stats);
  return stats;
}

int TrackBank::prune(StampNs stamp) {
  const auto before = tracks_.size();
  const double confirmed_timeout = config_.track_timeout_s;
  const double tentative_timeout = config_.tentative_timeout_s;
  tracks_.erase(std::remove_if(tracks_.begin(), tracks_.end(),
                               [&](const Track& t) {
                                 const double silent = secondsBetween(t.last_detection_ns, stamp);
                                 return silent > (t.confirmed ? confirmed_timeout : tentative_timeout);
                               }),
                tracks_.end());
  return static_cast<int>(before - tracks_.size());
}

}  // namespace swa::agent

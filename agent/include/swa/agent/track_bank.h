#pragma once
// Model of surroundings (paper §III-A): one constant-acceleration LKF per neighbour, in the focal UAV's stable
// frame. Identified detections go to the track with their ID; anonymous detections are associated by a chi-square
// gate on the Mahalanobis distance and a global nearest-neighbour assignment. Tracks are tentative until they have
// `confirm_hits` detections, so isolated clutter never becomes a neighbour.

#include <vector>

#include "swa/agent/assignment.h"
#include "swa/agent/config.h"
#include "swa/agent/pva_model.h"
#include "swa/agent/samples.h"

namespace swa::agent {

// Anonymous tracks get IDs from here up, well above any real UAV ID (limits.max_target_id).
constexpr int kFirstAnonymousTrackId = 1'000'000'000;

struct StableDetection {
  int target_id = kAnonymousId;
  Vec2 position_m = Vec2::Zero();  // stable frame, relative to the focal UAV
  Mat2 covariance_m2 = Mat2::Identity();
};

struct Track {
  int id = 0;
  bool anonymous = false;
  bool confirmed = false;
  int hits = 0;
  StampNs created_ns = 0;
  StampNs last_detection_ns = 0;
  StampNs time_ns = 0;  // the time the estimate refers to
  PvaState estimate;

  Vec2 position() const { return segment<pva::Pos>(estimate.x); }
  Vec2 velocity() const { return segment<pva::Vel>(estimate.x); }
};

struct BankUpdateStats {
  int corrected = 0;
  int created = 0;
  int reinitialised = 0;  // an identified track whose detection fell far outside its gate
  int removed = 0;
  int dropped_capacity = 0;
};

class TrackBank {
 public:
  explicit TrackBank(const SurroundingsConfig& config);

  // Predicts every track to `stamp`, associates and corrects, then starts and prunes tracks.
  BankUpdateStats update(StampNs stamp, const std::vector<StableDetection>& detections);

  const std::vector<Track>& tracks() const { return tracks_; }
  const Track* find(int id) const;
  int confirmedCount() const;
  int tentativeCount() const;
  // For each detection of the last update: the id of the track it updated or started, or -1 when dropped.
  const std::vector<int>& lastTrackOfDetection() const { return last_track_of_detection_; }

  static constexpr std::size_t kMaxTracks = 128;

 private:
  void predict(Track& track, StampNs stamp);
  bool correct(Track& track, const StableDetection& det, StampNs stamp);
  bool correct(Track& track, const StableDetection& det, const Innovation<2>& in, StampNs stamp);
  int startTrack(const StableDetection& det, StampNs stamp, bool anonymous);
  void associateAnonymous(const std::vector<StableDetection>& detections, StampNs stamp, BankUpdateStats& stats);
  void assignPass(const std::vector<StableDetection>& detections, StampNs stamp, BankUpdateStats& stats);
  int prune(StampNs stamp);

  SurroundingsConfig config_;
  PvaNoise noise_;
  double gate_;         // chi-square(2) quantile of gate_probability
  double reinit_gate_;  // far outside any plausible innovation: the sensor's ID was right, our track was wrong
  std::vector<Track> tracks_;
  double cached_dt_ = -1.0;
  PvaMat F_, Q_;
  int next_anonymous_id_ = kFirstAnonymousTrackId;
  std::vector<int> last_track_of_detection_;
  // Association workspace, reused between updates.
  std::vector<int> anon_tracks_, free_dets_;
  std::vector<double> cost_;
  std::vector<char> taken_;
  Assignment assignment_;
};

}  // namespace swa::agent

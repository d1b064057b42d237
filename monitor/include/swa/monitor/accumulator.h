#pragma once
// Time series and run summary: MetricsAccumulator takes the steps of one run in time order and keeps what the
// summary needs (collision contacts, a short centroid history, the last `final_window_s` of d_NB, window sums).
// Memory is bounded by the windows, not by the run length.

#include <cstdint>
#include <deque>
#include <map>
#include <set>
#include <utility>
#include <vector>

#include "swa/monitor/chi2.h"
#include "swa/monitor/mission_score.h"
#include "swa/monitor/swarm_metrics.h"

namespace swa::monitor {

struct StepMetrics {
  double t_s = 0.0;
  Geometry geometry;
  NeesStep nees;
  std::uint64_t collisions = 0;  // cumulative collision onsets since the first step
  int new_collisions = 0;        // onsets at this step
  // Centroid speed over the last drift_window_s: |c(t) - c(t')| / (t - t') with t' the latest step at least
  // drift_window_s back. NaN until that much history exists. The centroid is over the UAVs present at each step, so
  // a UAV dropping out shows up here as a jump.
  double drift_mps = kNaN;
};

// One run. "Window" = from the first step at or after config.window_start_s to the last step. Counts are stored as
// doubles only in the flat key/value view (report.h); here they keep their type.
struct Summary {
  int steps = 0;
  double duration_s = kNaN;      // last step time - first step time
  double window_start_s = kNaN;  // time of the first step in the window (NaN: the run never reached it)
  double window_duration_s = kNaN;
  int uav_count = 0;                       // present at the last step
  double mean_neighbor_distance_m = kNaN;  // mean of the per-step d_NB over the last final_window_s
  double formation_error_m = kNaN;         // mean of the per-step formation error over the last final_window_s
  double edge_length_m = kNaN;             // mean of the per-step Gabriel edge length over the last final_window_s
  double min_separation_m = kNaN;          // minimum over the whole run
  std::uint64_t collisions = 0;            // onsets over the whole run
  // Over the UAVs present at both ends of the window: |mean_i (p_i(end) - p_i(start))| / window duration, i.e. the
  // net displacement of the centroid of a fixed set of UAVs (a UAV dropping out does not move it).
  double drift_velocity_mps = kNaN;
  // The same net-centroid speed over each complete drift_segment_s stretch of the window (consecutive, from its
  // start; a trailing partial stretch is left out), averaged. Unlike drift_velocity_mps it does not fall as 1/T for
  // a swarm that wanders back and forth, so runs of different lengths compare. NaN until one stretch is complete.
  double drift_velocity_windows_mps = kNaN;
  double centroid_displacement_m = kNaN;  // the same mean displacement, as a distance
  double uav_displacement_m = kNaN;       // mean_i |p_i(end) - p_i(start)| over the same UAVs
  double drift_speed_max_mps = kNaN;      // largest time-series drift_mps inside the window
  int groups = 0;                         // at the last step
  double spread_m = kNaN;                 // at the last step
  // ANEES: time average over the window steps with at least one evaluated agent of the per-step mean NEES.
  double anees_position = kNaN;
  double anees_velocity = kNaN;
  // The chi-square band for a mean over K agents of 2-dof NEES (aneesBand(K, 2, alpha)), K = the mean number
  // of agents evaluated per contributing step, rounded. Time averaging does not narrow it: successive steps are
  // strongly correlated, so the band is the per-step one.
  int anees_agents = 0;
  double anees_band_low = kNaN;
  double anees_band_high = kNaN;
  // Fraction of contributing steps whose mean NEES lies in the band for that step's own K.
  double anees_position_in_band = kNaN;
  double anees_velocity_in_band = kNaN;
  int nees_steps = 0;                         // contributing steps
  std::uint64_t nees_samples = 0;             // agent-estimates evaluated in the window
  std::uint64_t nees_skipped_unknown_id = 0;  // in the window
  std::uint64_t nees_skipped_invalid = 0;     // in the window
  // A mission's figures (mission_score.h); NaN without a mission or before it started.
  double mission_end_error_m = kNaN;
  double mission_path_error_m = kNaN;
  double mission_d_nb_moving_m = kNaN;
  double mission_uav_end_error_m = kNaN;
  double mission_uav_end_spread_m = kNaN;
};

class MetricsAccumulator {
 public:
  // Throws std::invalid_argument on a bad config (validate()).
  explicit MetricsAccumulator(const MetricsConfig& config = MetricsConfig{});

  // Adds one step and returns its metrics (valid until the next add). Throws std::invalid_argument when the stamp is
  // earlier than the previous one, ids repeat, or estimates do not match uavs; the accumulator is then unchanged.
  const StepMetrics& add(const StepInput& step);

  Summary summary() const;
  const MetricsConfig& config() const { return config_; }
  // A mission changed live (mission_score.h, replanMission): scored against `legs` from `start_s` on.
  void replanMission(const std::vector<agent::MissionLeg>& legs, double start_s);
  int steps() const { return steps_; }

 private:
  struct FinalSample {
    agent::StampNs stamp_ns;
    double d_nb;
    double formation_error;
    double edge_length;
  };
  // Adds the stretch ending at `stamp` to the drift segments if it is complete; true when it was.
  bool closeDriftSegment(agent::StampNs stamp);
  double finalMean(double FinalSample::*field) const;

  int updateCollisions(const StepInput& step);
  double updateDrift(agent::StampNs stamp, const Geometry& geometry);
  const AneesBand& bandFor(int k);

  MetricsConfig config_;
  agent::StampNs window_start_ns_;
  agent::StampNs final_window_ns_;
  agent::StampNs drift_window_ns_;

  int steps_ = 0;
  agent::StampNs first_ns_ = 0;
  agent::StampNs last_ns_ = 0;
  StepMetrics last_;

  std::set<std::pair<int, int>> contacts_;  // id pairs (low, high) currently in collision
  std::uint64_t collisions_ = 0;
  double min_separation_m_ = kNaN;

  std::deque<std::pair<agent::StampNs, agent::Vec2>> centroid_history_;
  std::deque<FinalSample> final_samples_;

  bool window_started_ = false;
  agent::StampNs window_first_ns_ = 0;
  std::map<int, agent::Vec2> window_start_positions_;
  std::map<int, agent::Vec2> last_positions_;
  agent::StampNs drift_segment_ns_;
  agent::StampNs segment_first_ns_ = 0;
  std::map<int, agent::Vec2> segment_start_positions_;
  double segment_speed_sum_ = 0.0;
  int segments_ = 0;
  double drift_max_mps_ = kNaN;

  double nees_pos_sum_ = 0.0;
  double nees_vel_sum_ = 0.0;
  int nees_steps_ = 0;
  std::uint64_t nees_samples_ = 0;
  int pos_in_band_ = 0;
  int vel_in_band_ = 0;
  std::uint64_t skipped_unknown_ = 0;
  std::uint64_t skipped_invalid_ = 0;
  std::vector<AneesBand> bands_;  // bands_[k - 1] for k agents, filled on demand
  MissionScore mission_;
};

}  // namespace swa::monitor

#pragma once
// Per-step swarm metrics from ground truth (DESIGN §1 monitor, §5 reference numbers) and the NEES of the agents'
// focal estimates against truth. Pure functions of one step's data: no clock, no DDS, no state; the time series and
// the run summary are built on top of them by MetricsAccumulator (accumulator.h).
//
// Conventions: world frame W, metres and seconds; all stable frames are aligned with W (DESIGN §2), so "relative to
// UAV i in its stable frame" is simply p_j - p_i. A quantity that is undefined for the step (d_NB of a single UAV,
// NEES with no agent to evaluate) is NaN, never a made-up number.

#include <array>
#include <cstdint>
#include <limits>
#include <vector>

#include "swa/agent/config.h"
#include "swa/agent/diagnostics.h"
#include "swa/agent/frame_fit.h"
#include "swa/agent/geometry.h"
#include "swa/agent/samples.h"

namespace swa::monitor {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Ground truth of one UAV at one step.
struct UavTruth {
  int id = 0;  // the id the agents' detections carry for this UAV (the sim's UAV index); unique within a step
  agent::Vec2 position_m = agent::Vec2::Zero();  // world frame
  agent::Vec2 velocity_mps = agent::Vec2::Zero();
  // In the air and part of the swarm. false (or a non-finite position/velocity) removes the UAV from every metric of
  // the step; a UAV whose agent died but which still hovers under the sim's failsafe is in the air: keep it alive.
  bool alive = true;
};

// alive with finite position and velocity: the UAVs every metric is computed over.
inline bool isPresent(const UavTruth& u) {
  return u.alive && agent::isFinite(u.position_m) && agent::isFinite(u.velocity_mps);
}

// What one agent reports about its focal estimate (a subset of agent::Diagnostics plus the frame parameters needed
// to rebuild its floating frame from truth).
struct EstimateRecord {
  bool valid = false;                            // false: the agent has no floating-frame estimate this step
  agent::Vec2 position_m = agent::Vec2::Zero();  // p̂: own position in the floating frame F
  agent::Mat2 position_cov_m2 = agent::Mat2::Zero();
  agent::Vec2 velocity_mps = agent::Vec2::Zero();  // v̂: own velocity relative to F
  agent::Mat2 velocity_cov_m2ps2 = agent::Mat2::Zero();
  int neighbour_count = 0;  // neighbours the frame was fitted on
  std::array<int, agent::kMaxNeighbours> neighbour_ids{};
  agent::FormationConfig formation;  // that agent's: its radius and circle fit rebuild its frame
};

// The record of an agent's diagnostics. valid only when the estimate is a floating-frame one that is being tracked:
// mode swa or anchored (standalone estimates live in the take-off frame), stage kTracking, frame valid, at least one
// neighbour. Matching the diagnostics' stamp to the truth step is the caller's business.
EstimateRecord estimateFromDiagnostics(const agent::Diagnostics& diagnostics, const agent::FormationConfig& formation);

// One time step as the monitor sees it.
struct StepInput {
  agent::StampNs stamp_ns = 0;
  std::vector<UavTruth> uavs;
  std::vector<EstimateRecord> estimates;  // empty (no NEES), or exactly one per entry of `uavs`, in the same order
};

// How the velocity of UAV i relative to its floating frame is obtained from truth.
enum class FrameVelocity : std::uint8_t {
  // v_i - mean_j v_j over the frame's neighbours. Exact when the neighbours move as a rigid translation (then the
  // frame translates with them, whatever the fit), which is the steady state of a formation; it ignores the frame
  // motion caused by neighbours moving relative to each other or, for n = 1, by self moving around the neighbour.
  kNeighbourMean,
  // -d r_c/dt, with r_c = fit(p_j - p_i): the directional derivative of the same fit the agent runs, by a central
  // difference of 1 cm along the relative velocities. This is the quantity the focal filter estimates. Falls back to
  // kNeighbourMean (and says so) when the stencil crosses a change of fit case.
  kFitDerivative
};

// The monitor's PASS band for the final d_NB, as a fraction of r (DESIGN §5: the Gabriel rule holds ±3 % for 3 to 16
// UAVs, so ±5 % leaves room for noise, not for a squeezed formation).
constexpr double kDefaultRadiusTolerance = 0.05;

struct MetricsConfig {
  // The agents' formation (the scenario's agent.formation): r is the group link distance, the formation error's
  // target and the verdict's. The one copy of r from the scenario to the record, the verdict and the report.
  agent::FormationConfig formation;
  double radius_tolerance = kDefaultRadiusTolerance;  // PASS band of the final d_NB: r × (1 ± this)
  double collision_distance_m = 1.5;                  // a pair closer than this is in collision
  double collision_release_m = 0.5;  // hysteresis: the contact ends once the pair is farther than distance + this,
                                     // so a pair jittering around the threshold is one collision, not ten
  double group_link_factor = 1.5;    // UAVs closer than factor * r are linked into one group
  int distance_neighbours = 2;       // d_NB and formation error use each UAV's this many nearest others
  double window_start_s = 0.0;       // drift, displacement and ANEES window start (the GNSS-loss time)
  double final_window_s = 5.0;       // d_NB and formation error "at the end": mean over this last stretch
  double drift_window_s = 1.0;       // time-series drift: centroid speed over this last stretch
  double drift_segment_s = 60.0;     // summary drift_velocity_windows_mps: mean over consecutive windows this long
  double anees_alpha = 0.05;         // two-sided ANEES acceptance band (1 - alpha)
  FrameVelocity frame_velocity = FrameVelocity::kNeighbourMean;
  // A mission (issue #45): the agents' plan and when its first leg begins on the steps' clock; no legs: none.
  std::vector<agent::MissionLeg> mission_legs;
  double mission_start_s = 0.0;
};

// Every problem in one message; throws std::invalid_argument if there is any.
void validate(const MetricsConfig& config);

// Geometry of the UAVs present at one step.
struct Geometry {
  int uav_count = 0;  // present UAVs (alive, finite truth)
  // d_NB: for each UAV the mean distance to its `distance_neighbours` nearest others (all others when fewer),
  // averaged over UAVs. NaN with fewer than 2 UAVs.
  double mean_neighbor_distance_m = kNaN;
  agent::Vec2 centroid_m = agent::Vec2::Constant(kNaN);  // mean position; NaN with no UAV
  double min_separation_m = kNaN;                        // smallest pairwise distance; NaN with fewer than 2 UAVs
  double spread_m = kNaN;                                // largest distance from the centroid; 0 for one UAV
  int groups = 0;                                        // connected components linking UAVs closer than factor * r
  // Formation error: for each UAV the mean of |d_ij - r| over the same nearest others as d_NB, averaged over UAVs.
  // Not "nearest neighbour only": a pair exactly r apart but far from everyone else would score 0 there. Over the
  // d_NB set, formation_error >= |d_NB - r| (equality iff no distance lies on the other side of r), so it adds the
  // spread of the spacing to the bias that d_NB shows. NaN with fewer than 2 UAVs.
  double formation_error_m = kNaN;
  // Mean true length of the edges of the swarm's Gabriel graph (i-j is an edge when no other UAV lies in the disc
  // with diameter i-j; DESIGN §3.2). The spacing metric that does not read low for UAVs with 3-6 neighbours at r
  // (d_NB averages the two nearest, which are below r whenever the spacing varies at all). NaN with fewer than 2 UAVs.
  double edge_length_m = kNaN;
};

Geometry computeGeometry(const std::vector<UavTruth>& uavs, const MetricsConfig& config);

// Mean length of the edges of the Gabriel graph of `points` (agent::inDiametralDisc); NaN with fewer than 2 points.
// O(n^3): fine for swarms of tens.
double meanGabrielEdgeLength(const std::vector<agent::Vec2>& points);

// Connected components of the graph linking points closer than `link_distance_m` (strictly).
int countGroups(const std::vector<agent::Vec2>& positions, double link_distance_m);

enum class TruthStatus : std::uint8_t {
  kOk,
  kNoNeighbours,      // the record names no neighbour (or more than kMaxNeighbours)
  kUnknownNeighbour,  // a neighbour id is not a present UAV of the step (anonymous track id >= 1e9, dead, self, ...)
  kSelfAbsent,        // the estimating UAV itself is not present in the truth
  kFitFailed          // the frame fit on the true positions gave no frame
};

// Where UAV `self` truly is (and how it truly moves) in the floating frame it reported: the frame is refitted with
// agent::fitFloatingFrame on the TRUE positions of the reported neighbours relative to `self`, in the record's order
// (the agent's ranking, nearest first by its own estimates: the weighted fit's weights go by it), with the record's
// radius and method.
struct TruthInFrame {
  TruthStatus status = TruthStatus::kNoNeighbours;
  agent::Vec2 position_m = agent::Vec2::Constant(kNaN);  // = -r_c
  agent::Vec2 velocity_mps = agent::Vec2::Constant(kNaN);
  agent::FitCase fit_case = agent::FitCase::kNone;
  bool velocity_fallback = false;  // kFitDerivative asked for, kNeighbourMean used (fit case changed in the stencil)
  bool ok() const { return status == TruthStatus::kOk; }
};

TruthInFrame truthInFloatingFrame(const UavTruth& self, const std::vector<UavTruth>& uavs, const EstimateRecord& record,
                                  FrameVelocity method);

// e' P^-1 e (solved, not inverted). NaN unless e is finite and P passes agent::isCovariance.
double nees(const agent::Vec2& error, const agent::Mat2& covariance);

// NEES of the agents' estimates at one step. Every valid record, and every present UAV's record, lands in exactly
// one of the counters below.
struct NeesStep {
  double position = kNaN;      // mean position NEES over the evaluated agents (NaN when none)
  double velocity = kNaN;      // mean velocity NEES over the same agents
  int evaluated = 0;           // agents with both NEES computed
  int skipped_unknown_id = 0;  // valid estimate, but a reported neighbour is not in the truth
  int skipped_invalid = 0;     // valid estimate, but unusable: covariance not positive definite, non-finite values,
                               // no neighbours, self absent, or no frame from the true positions
  int no_estimate = 0;         // present UAVs whose record is not valid
};

// Requires step.estimates empty or the same size as step.uavs (throws std::invalid_argument otherwise).
NeesStep computeNees(const StepInput& step, FrameVelocity method);

}  // namespace swa::monitor

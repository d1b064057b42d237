#pragma once
// Neighbourhood selection (DESIGN §3.2): which confirmed tracks within sensing range define the floating frame.
//
// - k_nearest: the k nearest.
// - gabriel: track j is a neighbour when no other confirmed track m lies in the closed disc with the segment
//   self -> j as diameter, i.e. p_m . (p_j - p_m) >= 0 fails for every m (the angle self-m-j is acute). On a
//   triangular lattice this is exactly the lattice edges (a second-shell UAV at sqrt(3) r has two first-shell UAVs
//   inside its disc); on a square lattice the diagonals have the two corners on the circle and are excluded. The
//   nearest track always passes. A neighbour other than the nearest must also be closer than max_edge_factor * r:
//   when the UAV between self and a second-shell UAV is untracked (outside the field of view, missed), the test
//   alone would let the second-shell UAV through and the fit would pull it to r.
//
// Both rules list the neighbours nearest first; ties in distance are broken by track id, so the choice never
// depends on the order tracks were created in.

#include <array>
#include <vector>

#include "swa/agent/config.h"
#include "swa/agent/frame_fit.h"
#include "swa/agent/track_bank.h"

namespace swa::agent {

struct Neighbourhood {
  NeighbourPositions positions;           // nearest first
  std::array<int, kMaxNeighbours> ids{};  // same order
  NeighbourCovariances covariances{};     // same order: the tracks' position covariances
  int count() const { return positions.count; }
  // Whether both define the same floating frame: the same ids, and with a `ranked` fit (weights by rank, see
  // frame_fit.h) the same two nearest.
  bool sameFrameAs(const Neighbourhood& other, bool ranked) const;
};

Neighbourhood selectNeighbours(const std::vector<Track>& tracks, const FormationConfig& formation);

// The rules on their own, for the tests and the benchmark.
Neighbourhood selectKNearest(const std::vector<Track>& tracks, int k, double sensing_range_m);
Neighbourhood selectGabriel(const std::vector<Track>& tracks, double sensing_range_m, double max_edge_m);

// Current positions of a previously chosen neighbour set, if every one of them is still tracked and confirmed.
bool positionsOf(const std::vector<Track>& tracks, const Neighbourhood& chosen, NeighbourPositions& out);

}  // namespace swa::agent

#pragma once
// Neighbourhood selection (DESIGN §3.2): the k nearest confirmed tracks within sensing range. Ties in distance are
// broken by track id so the choice never depends on the order tracks were created in.

#include <array>

#include "swa/agent/frame_fit.h"
#include "swa/agent/track_bank.h"

namespace swa::agent {

struct Neighbourhood {
  NeighbourPositions positions;            // nearest first
  std::array<int, kMaxNeighbours> ids{};   // same order
  int count() const { return positions.count; }
  bool sameIdsAs(const Neighbourhood& other) const;
};

Neighbourhood selectNeighbours(const std::vector<Track>& tracks, int k, double sensing_range_m);

// Current positions of a previously chosen neighbour set, if every one of them is still tracked and confirmed.
bool positionsOf(const std::vector<Track>& tracks, const Neighbourhood& chosen, NeighbourPositions& out);

}  // namespace swa::agent

#pragma once
// Initial formation: slots of a triangular (hexagonal) lattice, the densest packing at a given neighbour spacing.

#include <vector>

#include "swa/agent/geometry.h"

namespace swa::sim {

// The n lattice points closest to the origin (ties broken by angle counter-clockwise from +x), so the cluster fills
// ring after ring and stays as compact as the lattice allows. Slot 0 is the origin and slot 1 is (spacing, 0).
// Deterministic: the ordering is computed on integer lattice norms, not on rounded distances.
std::vector<agent::Vec2> hexLattice(int n, double spacing_m);

}  // namespace swa::sim

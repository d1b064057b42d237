#include "swa/agent/neighbourhood.h"

#include <algorithm>

namespace swa::agent {

bool Neighbourhood::sameIdsAs(const Neighbourhood& other) const {
  if (count() != other.count()) return false;
  // Order is by distance and may swap without the set changing; the set is what defines the frame.
  for (int i = 0; i < count(); ++i) {
    bool found = false;
    for (int j = 0; j < other.count() && !found; ++j) found = ids[i] == other.ids[j];
    if (!found) return false;
  }
  return true;
}

Neighbourhood selectNeighbours(const std::vector<Track>& tracks, int k, double sensing_range_m) {
  struct Candidate {
    double dist2;
    int id;
    Vec2 position;
  };
  std::array<Candidate, kMaxNeighbours> best{};
  const int wanted = std::clamp(k, 0, kMaxNeighbours);
  int n = 0;
  const double range2 = sensing_range_m * sensing_range_m;
  auto better = [](const Candidate& a, const Candidate& b) {
    return a.dist2 < b.dist2 || (a.dist2 == b.dist2 && a.id < b.id);
  };
  // Insertion into a small sorted array: k <= 16 and tracks <= 128, cheaper than sorting all tracks.
  for (const Track& t : tracks) {
    if (!t.confirmed) continue;
    const Vec2 p = t.position();
    const Candidate c{p.squaredNorm(), t.id, p};
    if (c.dist2 > range2) continue;
    if (n < wanted) {
      best[n++] = c;
    } else if (n > 0 && better(c, best[n - 1])) {
      best[n - 1] = c;
    } else {
      continue;
    }
    for (int i = n - 1; i > 0 && better(best[i], best[i - 1]); --i) std::swap(best[i], best[i - 1]);
  }
  Neighbourhood out;
  out.positions.count = n;
  for (int i = 0; i < n; ++i) {
    out.positions.position[i] = best[i].position;
    out.ids[i] = best[i].id;
  }
  return out;
}

bool positionsOf(const std::vector<Track>& tracks, const Neighbourhood& chosen, NeighbourPositions& out) {
  out.count = chosen.count();
  for (int i = 0; i < chosen.count(); ++i) {
    auto it = std::find_if(tracks.begin(), tracks.end(), [&](const Track& t) { return t.id == chosen.ids[i]; });
    if (it == tracks.end() || !it->confirmed) return false;
    out.position[i] = it->position();
  }
  return true;
}

}  // namespace swa::agent

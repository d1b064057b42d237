#include "swa/agent/neighbourhood.h"

#include <algorithm>

namespace swa::agent {
namespace {

struct Candidate {
  double dist2;
  int id;
  Vec2 position;
  const Track* track;
};

bool nearer(const Candidate& a, const Candidate& b) { return a.dist2 < b.dist2 || (a.dist2 == b.dist2 && a.id < b.id); }

// Gabriel's test is O(n^2) over every confirmed track, so it sees at most this many (nearest first); the bank
// holds at most TrackBank::kMaxTracks.
constexpr std::size_t kMaxWitnesses = TrackBank::kMaxTracks;

Neighbourhood fromCandidates(const Candidate* c, int n) {
  Neighbourhood out;
  out.positions.count = n;
  for (int i = 0; i < n; ++i) {
    out.positions.position[i] = c[i].position;
    out.ids[i] = c[i].id;
    out.covariances[i] = block<pva::Pos, pva::Pos>(c[i].track->estimate.P);
  }
  return out;
}

}  // namespace

namespace {

bool sameSet(const int* a, const int* b, int count) {
  for (int i = 0; i < count; ++i) {
    bool found = false;
    for (int j = 0; j < count && !found; ++j) found = a[i] == b[j];
    if (!found) return false;
  }
  return true;
}

}  // namespace

bool Neighbourhood::sameFrameAs(const Neighbourhood& other, bool ranked) const {
  if (count() != other.count()) return false;
  // Order is by distance and may swap without the set changing. Unweighted, the set alone defines the frame; with
  // the weighted fit, so does which two of them are the nearest (weight 1).
  if (!sameSet(ids.data(), other.ids.data(), count())) return false;
  if (!ranked || count() < 3) return true;
  return sameSet(ids.data(), other.ids.data(), 2);
}

Neighbourhood selectKNearest(const std::vector<Track>& tracks, int k, double sensing_range_m) {
  std::array<Candidate, kMaxNeighbours> best{};
  const int wanted = std::clamp(k, 0, kMaxNeighbours);
  int n = 0;
  const double range2 = sensing_range_m * sensing_range_m;
  // Insertion into a small sorted array: k <= 16 and tracks <= 128, cheaper than sorting all tracks.
  for (const Track& t : tracks) {
    if (!t.confirmed) continue;
    const Vec2 p = t.position();
    const Candidate c{p.squaredNorm(), t.id, p, &t};
    if (c.dist2 > range2) continue;
    if (n < wanted) {
      best[n++] = c;
    } else if (n > 0 && nearer(c, best[n - 1])) {
      best[n - 1] = c;
    } else {
      continue;
    }
    for (int i = n - 1; i > 0 && nearer(best[i], best[i - 1]); --i) std::swap(best[i], best[i - 1]);
  }
  return fromCandidates(best.data(), n);
}

Neighbourhood selectGabriel(const std::vector<Track>& tracks, double sensing_range_m, double max_edge_m) {
  // Every confirmed track is a witness, also beyond sensing range; nearest first, because only a track nearer than
  // j can lie inside j's disc (the disc is within |p_j| of self).
  std::array<Candidate, kMaxWitnesses> all;
  std::size_t n = 0;
  for (const Track& t : tracks) {
    if (!t.confirmed || n == all.size()) continue;
    const Vec2 p = t.position();
    all[n++] = Candidate{p.squaredNorm(), t.id, p, &t};
  }
  std::sort(all.begin(), all.begin() + static_cast<std::ptrdiff_t>(n), nearer);

  std::array<Candidate, kMaxNeighbours> chosen{};
  int count = 0;
  const double range2 = sensing_range_m * sensing_range_m;
  const double edge2 = max_edge_m * max_edge_m;
  for (std::size_t j = 0; j < n && count < kMaxNeighbours; ++j) {
    const Candidate& cj = all[j];
    if (cj.dist2 > range2) break;
    if (count > 0 && cj.dist2 >= edge2) break;  // sorted: every farther track is longer still
    bool blocked = false;
    for (std::size_t m = 0; m < j && !blocked; ++m) {
      blocked = inDiametralDisc(Vec2::Zero(), cj.position, all[m].position);
    }
    if (!blocked) chosen[static_cast<std::size_t>(count++)] = cj;
  }
  return fromCandidates(chosen.data(), count);
}

Neighbourhood selectNeighbours(const std::vector<Track>& tracks, const FormationConfig& formation) {
  switch (formation.neighbourhood) {
    case NeighbourhoodRule::kKNearest:
      return selectKNearest(tracks, formation.k, formation.sensing_range_m);
    case NeighbourhoodRule::kGabriel:
      break;
  }
  return selectGabriel(tracks, formation.sensing_range_m, formation.max_edge_factor * formation.radius_m);
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

#pragma once
// Seeded random streams for the simulated world. Every (UAV, stream) pair owns its own std::mt19937_64, seeded from
// the scenario seed through std::seed_seq, so turning a sensor on, changing its rate or adding a new stream never
// changes the numbers any other stream draws: a run differs from its baseline only where the scenario differs.
//
// The distributions are written out here instead of using <random>'s: the standard fixes the engines and seed_seq
// bit for bit, but leaves std::normal_distribution & co. to the library, so libstdc++ and libc++ would give
// different runs from the same seed.

#include <cstdint>
#include <random>

namespace swa::sim {

// One value per independent source of randomness. Append new streams at the end: the numeric values are part of
// the seeding and renumbering them changes every run.
enum class Stream : std::uint32_t {
  kPlacement = 1,  // lattice jitter
  kHeading = 2,    // initial heading and turn rate
  kGust = 3,       // per-UAV wind gust (or the common gust, owner kWorldOwner)
  kImuBias = 4,
  kImuNoise = 5,  // tilt and heading white noise
  kMpsMiss = 6,
  kMpsNoise = 7,
  kMpsClutter = 8,
  kMpsOrder = 9,  // order of detections within a scan
  kGnssNoise = 10,
  kHeadingWalk = 11,  // the compass bias's random walk
  kMpsLatency = 12,   // the detection sets' latency jitter
  kAccelBias = 13,    // the accelerometer part's constant errors: attitude error, then the three biases
  kAccelNoise = 14,   // the accelerometer part's white noise
};

// Owner of the streams that belong to the whole world rather than one UAV (the common gust).
constexpr std::uint32_t kWorldOwner = 0xFFFF'FFFFu;

class Rng {
 public:
  // seed_seq{seed_lo, seed_hi, owner, stream}: the 64-bit seed is split because seed_seq keeps 32 bits per word.
  Rng(std::uint64_t seed, std::uint32_t owner, Stream stream);

  double uniform();  // [0, 1), 53 random bits
  double uniform(double lo, double hi);
  double normal();                   // N(0, 1), Box-Muller (pairs cached)
  int poisson(double mean);          // mean <= 0 gives 0
  std::size_t index(std::size_t n);  // uniform in [0, n), n > 0

 private:
  std::mt19937_64 engine_;
  bool have_spare_ = false;
  double spare_ = 0.0;
};

}  // namespace swa::sim

#include "swa/sim/random.h"

#include <algorithm>
#include <cmath>

namespace swa::sim {

namespace {
constexpr double kTwoPi = 6.283185307179586476925286766559;
// Knuth's multiplicative Poisson sampler needs exp(-mean) well above the smallest double; larger means are drawn as
// a sum of independent chunks (a sum of Poisson variables is Poisson).
constexpr double kPoissonChunk = 20.0;
}  // namespace

Rng::Rng(std::uint64_t seed, std::uint32_t owner, Stream stream) {
  std::seed_seq seq{static_cast<std::uint32_t>(seed & 0xFFFF'FFFFu), static_cast<std::uint32_t>(seed >> 32), owner,
                    static_cast<std::uint32_t>(stream)};
  engine_.seed(seq);
}

double Rng::uniform() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }

double Rng::uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }

double Rng::normal() {
  if (have_spare_) {
    have_spare_ = false;
    return spare_;
  }
  const double u1 = 1.0 - uniform();  // (0, 1]: log stays finite
  const double u2 = uniform();
  const double r = std::sqrt(-2.0 * std::log(u1));
  spare_ = r * std::sin(kTwoPi * u2);
  have_spare_ = true;
  return r * std::cos(kTwoPi * u2);
}

int Rng::poisson(double mean) {
  int count = 0;
  double remaining = mean;
  while (remaining > 0.0) {
    const double chunk = std::min(remaining, kPoissonChunk);
    remaining -= chunk;
    const double limit = std::exp(-chunk);
    double product = uniform();
    while (product > limit) {
      ++count;
      product *= uniform();
    }
  }
  return count;
}

std::size_t Rng::index(std::size_t n) {
  const auto i = static_cast<std::size_t>(uniform() * static_cast<double>(n));
  return std::min(i, n - 1);
}

}  // namespace swa::sim

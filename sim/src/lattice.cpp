#include "swa/sim/lattice.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace swa::sim {

namespace {

struct LatticePoint {
  std::int64_t norm2;  // |i a1 + j a2|^2 / spacing^2 = i^2 + ij + j^2, exact in integers
  double angle;        // [0, 2 pi)
  double x, y;         // in units of spacing
};

}  // namespace

std::vector<agent::Vec2> hexLattice(int n, double spacing_m) {
  std::vector<agent::Vec2> slots;
  if (n <= 0) return slots;
  // The n nearest points lie within Euclidean radius ~0.53 sqrt(n) spacings, hence within |i|, |j| <= 0.83 sqrt(n):
  // a box of half-width ceil(sqrt(n)) + 1 holds all of them.
  const auto half = static_cast<std::int64_t>(std::ceil(std::sqrt(static_cast<double>(n)))) + 1;
  const double sqrt3_2 = std::sqrt(3.0) / 2.0;
  std::vector<LatticePoint> points;
  points.reserve(static_cast<std::size_t>((2 * half + 1) * (2 * half + 1)));
  for (std::int64_t i = -half; i <= half; ++i) {
    for (std::int64_t j = -half; j <= half; ++j) {
      const double x = static_cast<double>(i) + 0.5 * static_cast<double>(j);
      const double y = sqrt3_2 * static_cast<double>(j);
      double angle = std::atan2(y, x);
      if (angle < 0.0) angle += 2.0 * M_PI;
      points.push_back({i * i + i * j + j * j, angle, x, y});
    }
  }
  const auto count = static_cast<std::size_t>(n);
  std::partial_sort(points.begin(), points.begin() + static_cast<std::ptrdiff_t>(count), points.end(),
                    [](const LatticePoint& a, const LatticePoint& b) {
                      return a.norm2 != b.norm2 ? a.norm2 < b.norm2 : a.angle < b.angle;
                    });
  slots.reserve(count);
  for (std::size_t k = 0; k < count; ++k) slots.emplace_back(spacing_m * points[k].x, spacing_m * points[k].y);
  return slots;
}

}  // namespace swa::sim

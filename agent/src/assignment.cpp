#include "swa/agent/assignment.h"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace swa::agent {

const std::vector<int>& Assignment::solve(const std::vector<double>& cost, int rows, int cols) {
  result_.assign(static_cast<std::size_t>(rows), -1);
  if (rows == 0 || cols == 0) return result_;

  // Non-finite costs would make the potentials NaN and the augmenting search never terminate.
  for (const double c : cost) {
    if (!std::isfinite(c)) throw std::invalid_argument("Assignment::solve: non-finite cost");
  }
  // The potential method below needs rows <= cols; solve the transposed problem otherwise.
  const bool transpose = rows > cols;
  const int n = transpose ? cols : rows;
  const int m = transpose ? rows : cols;
  const double* a = cost.data();
  if (transpose) {
    transposed_.resize(static_cast<std::size_t>(n) * m);
    for (int i = 0; i < rows; ++i)
      for (int j = 0; j < cols; ++j)
        transposed_[static_cast<std::size_t>(j) * m + i] = cost[static_cast<std::size_t>(i) * cols + j];
    a = transposed_.data();
  }
  auto at = [a, m](int i, int j) { return a[static_cast<std::size_t>(i - 1) * m + (j - 1)]; };

  constexpr double kInf = std::numeric_limits<double>::infinity();
  // 1-based arrays; column 0 is the virtual start column of each augmenting search.
  u_.assign(n + 1, 0.0);
  v_.assign(m + 1, 0.0);
  p_.assign(m + 1, 0);
  way_.assign(m + 1, 0);
  for (int i = 1; i <= n; ++i) {
    p_[0] = i;
    int j0 = 0;
    minv_.assign(m + 1, kInf);
    used_.assign(m + 1, 0);
    do {
      used_[j0] = 1;
      const int i0 = p_[j0];
      double delta = kInf;
      int j1 = 0;
      for (int j = 1; j <= m; ++j) {
        if (used_[j]) continue;
        const double reduced = at(i0, j) - u_[i0] - v_[j];
        if (reduced < minv_[j]) {
          minv_[j] = reduced;
          way_[j] = j0;
        }
        if (minv_[j] < delta) {
          delta = minv_[j];
          j1 = j;
        }
      }
      for (int j = 0; j <= m; ++j) {
        if (used_[j]) {
          u_[p_[j]] += delta;
          v_[j] -= delta;
        } else {
          minv_[j] -= delta;
        }
      }
      j0 = j1;
    } while (p_[j0] != 0);
    do {  // augment along the alternating path back to the start column
      const int j1 = way_[j0];
      p_[j0] = p_[j1];
      j0 = j1;
    } while (j0 != 0);
  }

  for (int j = 1; j <= m; ++j) {
    if (p_[j] == 0) continue;
    const int row_small = p_[j] - 1;
    const int col_small = j - 1;
    if (transpose) {
      result_[col_small] = row_small;  // small-problem rows are original columns
    } else {
      result_[row_small] = col_small;
    }
  }
  return result_;
}

}  // namespace swa::agent

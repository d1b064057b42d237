#pragma once
// Rectangular minimum-cost assignment (Hungarian method with row/column potentials, O(n^2 m)). Used for global
// nearest-neighbour association of anonymous detections; the workspace is kept between calls so the 10 Hz bank
// update does not allocate once it has seen its largest problem.

#include <vector>

namespace swa::agent {

class Assignment {
 public:
  // cost is row-major rows x cols. Pairs that must never be chosen carry `forbidden` (a large finite cost, so the
  // arithmetic stays finite); they may still appear in the optimum when a row has no other option, and callers
  // drop them. Returns, per row, the assigned column or -1.
  const std::vector<int>& solve(const std::vector<double>& cost, int rows, int cols);

 private:
  std::vector<double> u_, v_, minv_;
  std::vector<int> p_, way_, row_of_col_, result_;
  std::vector<char> used_;
  std::vector<double> transposed_;
};

}  // namespace swa::agent

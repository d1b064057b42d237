#pragma once
// Named slices of the position/velocity/acceleration state used by every filter in the agent. Code indexes the
// state through these names only: a raw Q(3,3) is how the wrong noise gets tuned.

#include <Eigen/Core>

namespace swa::agent {

template <int Offset, int Size>
struct Slice {
  static constexpr int offset = Offset;
  static constexpr int size = Size;
};

// 2-D point mass: [position; velocity; acceleration], each in metres / seconds units of one frame.
namespace pva {
using Pos = Slice<0, 2>;
using Vel = Slice<2, 2>;
using Acc = Slice<4, 2>;
constexpr int kDim = 6;
static_assert(Acc::offset + Acc::size == kDim, "slices must tile the state");
}  // namespace pva

template <typename S, typename Derived>
auto segment(Eigen::MatrixBase<Derived>& v) {
  return v.template segment<S::size>(S::offset);
}
template <typename S, typename Derived>
auto segment(const Eigen::MatrixBase<Derived>& v) {
  return v.template segment<S::size>(S::offset);
}
template <typename Row, typename Col, typename Derived>
auto block(Eigen::MatrixBase<Derived>& m) {
  return m.template block<Row::size, Col::size>(Row::offset, Col::offset);
}
template <typename Row, typename Col, typename Derived>
auto block(const Eigen::MatrixBase<Derived>& m) {
  return m.template block<Row::size, Col::size>(Row::offset, Col::offset);
}

}  // namespace swa::agent

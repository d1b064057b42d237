#include "swa/agent/frame_fit.h"

#include <cmath>
#include <optional>

#include <Eigen/Cholesky>
#include <Eigen/LU>

namespace swa::agent {
namespace {

// Below this distance two points are treated as one: 1 mm is far below any relative-localisation accuracy.
constexpr double kCoincidentM = 1e-3;
// Reciprocal condition number of the 3x3 normal equations below which the algebraic fit is considered collinear.
constexpr double kMinRcond = 1e-10;
constexpr int kMaxNewtonIterations = 20;
constexpr double kNewtonStepTolM = 1e-9;

// Neighbours are sorted nearest first: the two nearest weigh 1, the rest `far_weight`.
double weightOf(int j, double far_weight) { return j < 2 ? 1.0 : far_weight; }

double fixedRadiusCost(const NeighbourPositions& nb, const Vec2& c, double radius, double far_weight) {
  double cost = 0.0;
  for (int j = 0; j < nb.count; ++j) {
    const double e = (nb.position[j] - c).norm() - radius;
    cost += weightOf(j, far_weight) * e * e;
  }
  return cost;
}

}  // namespace

FrameFit fitOne(const Vec2& p, double radius) {
  FrameFit fit;
  fit.valid = true;
  const double d = p.norm();
  if (d < kCoincidentM) {
    // Self on top of the neighbour: any direction is as good as another; pick -x so the result is reproducible.
    fit.centre = p + Vec2(-radius, 0.0);
    fit.fit_case = FitCase::kCoincident;
    return fit;
  }
  fit.centre = p - p * (radius / d);  // r from the neighbour along neighbour -> self
  fit.fit_case = FitCase::kOne;
  return fit;
}

FrameFit fitTwo(const Vec2& p1, const Vec2& p2, double radius) {
  const Vec2 mid = 0.5 * (p1 + p2);
  const Vec2 half = 0.5 * (p2 - p1);
  const double h = half.norm();
  if (h < kCoincidentM) {
    FrameFit fit = fitOne(mid, radius);
    fit.fit_case = FitCase::kCoincident;
    return fit;
  }
  FrameFit fit;
  fit.valid = true;
  if (h >= radius) {
    fit.centre = mid;
    fit.fit_case = FitCase::kTwoFarApart;
    return fit;
  }
  const Vec2 normal = Vec2(-half.y(), half.x()) / h;
  const double offset = std::sqrt(radius * radius - h * h);
  const Vec2 a = mid + offset * normal;
  const Vec2 b = mid - offset * normal;
  // Ties (self on the line through both neighbours) go to `a`, so the choice is deterministic.
  fit.centre = (b.squaredNorm() < a.squaredNorm()) ? b : a;
  fit.fit_case = FitCase::kTwo;
  return fit;
}

FrameFit fitAlgebraic(const NeighbourPositions& nb, double radius) {
  // Normal equations of A [a b c]' = B with rows [x y 1] and x^2 + y^2 - r^2; 3x3, so LDLT is cheap and exact
  // enough, and its reciprocal condition number tells collinear sets apart.
  Eigen::Matrix3d AtA = Eigen::Matrix3d::Zero();
  Eigen::Vector3d AtB = Eigen::Vector3d::Zero();
  for (int j = 0; j < nb.count; ++j) {
    const Vec2& p = nb.position[j];
    const Eigen::Vector3d row(p.x(), p.y(), 1.0);
    AtA.noalias() += row * row.transpose();
    AtB += row * (p.squaredNorm() - radius * radius);
  }
  const Eigen::LDLT<Eigen::Matrix3d> ldlt(AtA);
  if (ldlt.info() != Eigen::Success || !ldlt.isPositive() || ldlt.rcond() < kMinRcond) {
    FrameFit fit = fitTwo(nb.position[0], nb.position[1], radius);
    fit.fit_case = FitCase::kCollinearFallback;
    return fit;
  }
  const Eigen::Vector3d abc = ldlt.solve(AtB);
  FrameFit fit;
  fit.valid = abc.allFinite();
  fit.centre = Vec2(0.5 * abc.x(), 0.5 * abc.y());
  fit.fit_case = FitCase::kAlgebraic;
  if (!fit.valid) {
    fit = fitTwo(nb.position[0], nb.position[1], radius);
    fit.fit_case = FitCase::kCollinearFallback;
  }
  return fit;
}

FrameFit fitFixedRadius(const NeighbourPositions& nb, double radius, double far_weight) {
  // Started from the n = 2 point of the two nearest neighbours: from the Kasa centre Gauss-Newton falls into the
  // mirror solution on the far side of the neighbours and UAVs collide (DESIGN §3.3).
  FrameFit fit = fitTwo(nb.position[0], nb.position[1], radius);
  if (fit.fit_case == FitCase::kCoincident) return fit;
  Vec2 c = fit.centre;
  double cost = fixedRadiusCost(nb, c, radius, far_weight);
  int it = 0;
  for (; it < kMaxNewtonIterations; ++it) {
    // Newton on the weighted cost sum w (|p - c| - r)^2. Its Hessian adds to the Gauss-Newton term u u' the
    // residual's curvature (1 - r/|p - c|)(I - u u'). Gauss-Newton alone converges only linearly here, because the
    // residuals do not vanish at the optimum: it needed 16 iterations on average (a quarter hit the cap of 20) to
    // meet the tolerance, Newton needs 3-5. Where that Hessian is not positive definite (neighbours well inside
    // the circle, far from the optimum) the Gauss-Newton matrix, which always is, takes its place.
    Mat2 gn = Mat2::Zero();
    Mat2 curvature = Mat2::Zero();
    Vec2 gradient = Vec2::Zero();
    for (int j = 0; j < nb.count; ++j) {
      const Vec2 d = nb.position[j] - c;
      const double dist = d.norm();
      if (dist < kCoincidentM) continue;  // gradient undefined on the neighbour itself; the others decide
      const Vec2 u = d / dist;
      const double w = weightOf(j, far_weight);
      const Mat2 uu = u * u.transpose();
      gn.noalias() += w * uu;
      curvature.noalias() += (w * (1.0 - radius / dist)) * (Mat2::Identity() - uu);
      gradient -= (w * (dist - radius)) * u;
    }
    // A whisker of Levenberg damping keeps the 2x2 solve defined when all residual directions are parallel.
    gn.diagonal().array() += 1e-9 * (1.0 + gn.trace());
    const Mat2 newton = gn + curvature;
    // Positive definite and not nearly singular relative to its own scale (det ~ trace^2 / 4 when well conditioned).
    const bool newton_ok = newton(0, 0) > 0.0 && newton.determinant() > 1e-9 * newton.trace() * newton.trace();
    // Halve a step until the cost does not increase: a full step can overshoot near the two-fold ambiguity. A Newton
    // step that finds no descent (a nearly flat valley) is followed by the Gauss-Newton step, which always descends
    // for a small enough length.
    const auto descend = [&](Vec2 step) {
      if (!isFinite(step)) return std::optional<Vec2>();
      double new_cost = fixedRadiusCost(nb, c + step, radius, far_weight);
      for (int h = 0; h < 10 && new_cost > cost; ++h) {
        step *= 0.5;
        new_cost = fixedRadiusCost(nb, c + step, radius, far_weight);
      }
      if (new_cost > cost) return std::optional<Vec2>();
      c += step;
      cost = new_cost;
      return std::optional<Vec2>(step);
    };
    std::optional<Vec2> step = newton_ok ? descend(-newton.inverse() * gradient) : std::nullopt;  // closed-form 2x2
    if (!step) step = descend(-gn.inverse() * gradient);
    if (!step) break;
    if (step->norm() < kNewtonStepTolM) {
      ++it;
      break;
    }
  }
  fit.centre = c;
  fit.iterations = it;
  fit.fit_case = FitCase::kFixedRadius;
  return fit;
}

bool fitCovariance(const NeighbourPositions& nb, const NeighbourCovariances& cov, const FrameFit& fit, double radius,
                   double far_weight, Mat2& out) {
  out.setZero();
  switch (fit.fit_case) {
    case FitCase::kOne: {
      // r_c = p - r p/|p|: only the radial part of the neighbour's error moves the centre (exactly so at |p| = r).
      const Vec2& p = nb.position[0];
      const double d = p.norm();
      const Vec2 u = p / d;
      const Mat2 J = Mat2::Identity() - (radius / d) * (Mat2::Identity() - u * u.transpose());
      out = J * cov[0] * J.transpose();
      break;
    }
    case FitCase::kTwoFarApart:
      out = 0.25 * (cov[0] + cov[1]);
      break;
    case FitCase::kTwo:
    case FitCase::kFixedRadius:
    case FitCase::kCollinearFallback: {
      const int n = fit.fit_case == FitCase::kFixedRadius ? nb.count : 2;
      std::array<Vec2, kMaxNeighbours> u;
      Mat2 A = Mat2::Zero();
      for (int j = 0; j < n; ++j) {
        const Vec2 d = nb.position[j] - fit.centre;
        const double dist = d.norm();
        if (dist < kCoincidentM) return false;
        u[j] = d / dist;
        A.noalias() += weightOf(j, far_weight) * u[j] * u[j].transpose();
      }
      // Two neighbours on a line through the centre leave it free across the line: a little damping keeps the
      // solve defined and reports that direction as very uncertain rather than as known.
      A.diagonal().array() += 1e-6;
      const Eigen::LDLT<Mat2> ldlt(A);
      for (int j = 0; j < n; ++j) {
        const Mat2 J = ldlt.solve(weightOf(j, far_weight) * u[j] * u[j].transpose());
        out.noalias() += J * cov[j] * J.transpose();
      }
      break;
    }
    default:
      return false;
  }
  out = 0.5 * (out + out.transpose());
  return out.allFinite();
}

FrameFit fitFloatingFrame(const NeighbourPositions& nb, double radius, CircleFit method, double far_weight) {
  switch (nb.count) {
    case 0:
      return FrameFit{};
    case 1:
      return fitOne(nb.position[0], radius);
    case 2:
      return fitTwo(nb.position[0], nb.position[1], radius);
    default:
      return method == CircleFit::kAlgebraic ? fitAlgebraic(nb, radius) : fitFixedRadius(nb, radius, far_weight);
  }
}

}  // namespace swa::agent

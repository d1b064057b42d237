#include "swa/monitor/chi2.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace swa::monitor {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr double kTiny = std::numeric_limits<double>::min() / kEps;  // Lentz guard against a zero denominator

// Both tails are returned so the quantile search can work on whichever one is small: 1 - P loses every digit
// once P is within 1e-16 of one, which is exactly the upper-tail region a gate probability lives in.
struct GammaTails {
  double lower;  // P(a, x)
  double upper;  // Q(a, x) = 1 - P(a, x)
};

// Both expansions need O(sqrt(a)) terms near x ~ a; the cap scales with that so dof = 1e4 and beyond converge,
// while a genuinely non-converging loop still ends.
int maxIterations(double a) { return 1000 + static_cast<int>(50.0 * std::sqrt(a)); }

// P(a, x) = x^a e^-x / Γ(a+1) * Σ_n x^n / ((a+1)...(a+n)). Every term is positive, so it is accurate for x < a+1,
// where the terms shrink from the start.
double lowerBySeries(double a, double x) {
  double term = 1.0;
  double sum = 1.0;
  const int limit = maxIterations(a);
  for (int n = 1; n <= limit; ++n) {
    term *= x / (a + n);
    sum += term;
    if (term < sum * kEps) {
      return sum * std::exp(a * std::log(x) - x - std::lgamma(a + 1.0));
    }
  }
  throw std::runtime_error("regularizedGammaP: series did not converge");
}

// Q(a, x) = x^a e^-x / Γ(a) / (b0 + a1/(b1 + a2/(b2 + ...))) with b_n = x + 2n + 1 - a, a_n = -n (n - a),
// evaluated with the modified Lentz method. Converges fast for x >= a+1, where the series would not.
double upperByContinuedFraction(double a, double x) {
  auto guard = [](double v) { return std::fabs(v) < kTiny ? kTiny : v; };
  double f = guard(x + 1.0 - a);
  double c = f;
  double d = 0.0;
  const int limit = maxIterations(a);
  for (int n = 1; n <= limit; ++n) {
    const double an = -n * (n - a);
    const double bn = x + 2.0 * n + 1.0 - a;
    d = 1.0 / guard(bn + an * d);
    c = guard(bn + an / c);
    const double delta = c * d;
    f *= delta;
    if (std::fabs(delta - 1.0) < kEps) {
      return std::exp(a * std::log(x) - x - std::lgamma(a)) / f;
    }
  }
  throw std::runtime_error("regularizedGammaP: continued fraction did not converge");
}

GammaTails gammaTails(double a, double x) {
  if (x <= 0.0) return {0.0, 1.0};
  if (std::isinf(x)) return {1.0, 0.0};
  if (x < a + 1.0) {
    const double p = lowerBySeries(a, x);
    return {p, 1.0 - p};
  }
  const double q = upperByContinuedFraction(a, x);
  return {1.0 - q, q};
}

void requirePositiveDof(double dof, const char* who) {
  if (!(dof > 0.0) || std::isinf(dof)) throw std::invalid_argument(std::string(who) + ": dof must be finite and > 0");
}

}  // namespace

double regularizedGammaP(double a, double x) {
  if (!(a > 0.0) || std::isinf(a)) throw std::invalid_argument("regularizedGammaP: a must be finite and > 0");
  if (std::isnan(x)) throw std::invalid_argument("regularizedGammaP: x is NaN");
  return gammaTails(a, x).lower;
}

double chi2Cdf(double x, double dof) {
  requirePositiveDof(dof, "chi2Cdf");
  if (std::isnan(x)) throw std::invalid_argument("chi2Cdf: x is NaN");
  return gammaTails(0.5 * dof, 0.5 * x).lower;
}

double chi2Quantile(double p, double dof) {
  requirePositiveDof(dof, "chi2Quantile");
  if (!(p > 0.0 && p < 1.0)) throw std::invalid_argument("chi2Quantile: p must lie in (0, 1)");

  // Solve in u = ln x on the log of the relevant tail: near 0 the lower tail behaves like x^(dof/2), i.e. linear
  // in u, so Newton converges there where it would crawl in x; and a fixed step in u is a relative step in x,
  // which is the accuracy we promise at every scale from dof = 1 to dof = 1e4+.
  const double a = 0.5 * dof;
  const bool useLower = p <= 0.5;
  const double logTarget = useLower ? std::log(p) : std::log1p(-p);
  // g(u) increases with u and is zero at the quantile.
  auto g = [&](double u, GammaTails& tails) {
    tails = gammaTails(a, 0.5 * std::exp(u));
    return useLower ? std::log(tails.lower) - logTarget : logTarget - std::log(tails.upper);
  };
  // dg/du = x * pdf(x) / tail, kept in logs so neither factor overflows at large dof.
  auto gPrime = [&](double u, const GammaTails& tails) {
    const double halfX = 0.5 * std::exp(u);
    const double logXPdf = a * std::log(halfX) - halfX - std::lgamma(a);
    return std::exp(logXPdf - std::log(useLower ? tails.lower : tails.upper));
  };

  // Bracket around the mean with steps that double in u, so even extreme p are reached in a few dozen CDF calls.
  GammaTails tails{};
  double lo = std::log(dof);
  double hi = lo;
  const double logMin = std::log(std::numeric_limits<double>::min());
  const double logMax = std::log(std::numeric_limits<double>::max());
  for (double step = 1.0; g(lo, tails) > 0.0; step *= 2.0) {
    hi = lo;
    lo -= step;
    // The quantile is below the smallest normal double (e.g. p = 1e-300 at dof = 1): 0 is the nearest answer.
    if (lo < logMin) return 0.0;
  }
  for (double step = 1.0; g(hi, tails) < 0.0; step *= 2.0) {
    lo = hi;
    hi += step;
    if (hi > logMax) throw std::runtime_error("chi2Quantile: could not bracket the quantile");
  }

  // Safeguarded Newton: a step that leaves the bracket, or too many iterations, falls back to bisection, which
  // alone reaches the tolerance from any bracket in well under 100 halvings.
  constexpr double kTolU = 1e-13;
  double u = 0.5 * (lo + hi);
  for (int iter = 0; iter < 200; ++iter) {
    const double gu = g(u, tails);
    if (gu == 0.0) return std::exp(u);
    (gu < 0.0 ? lo : hi) = u;
    if (hi - lo <= kTolU) return std::exp(0.5 * (lo + hi));
    double next = u - gu / gPrime(u, tails);
    if (!std::isfinite(next) || next <= lo || next >= hi || iter >= 60) next = 0.5 * (lo + hi);
    if (std::fabs(next - u) <= kTolU) return std::exp(next);
    u = next;
  }
  throw std::runtime_error("chi2Quantile: did not converge");
}

AneesBand aneesBand(int runs_K, int state_dim, double alpha) {
  if (runs_K < 1 || state_dim < 1) throw std::invalid_argument("aneesBand: runs_K and state_dim must be >= 1");
  if (!(alpha > 0.0 && alpha < 1.0)) throw std::invalid_argument("aneesBand: alpha must lie in (0, 1)");
  const double k = static_cast<double>(runs_K);
  const double dof = k * static_cast<double>(state_dim);
  return {chi2Quantile(0.5 * alpha, dof) / k, chi2Quantile(1.0 - 0.5 * alpha, dof) / k};
}

}  // namespace swa::monitor

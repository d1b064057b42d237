#pragma once
// Chi-square toolkit for the ANEES acceptance band. Self-contained on purpose: the agent
// core must not pull in Boost or a stats library for two numbers that are computed once per configuration.

namespace swa::monitor {

// Lower regularized incomplete gamma P(a, x) = γ(a, x) / Γ(a). Requires a > 0; x <= 0 gives 0, x = +inf gives 1.
// Throws std::invalid_argument on a <= 0 or NaN input.
double regularizedGammaP(double a, double x);

// P(X <= x) for X ~ chi2(dof). dof may be non-integer; throws std::invalid_argument on dof <= 0 or NaN.
double chi2Cdf(double x, double dof);

// The x with chi2Cdf(x, dof) = p, to ~1e-12 relative. Throws std::invalid_argument unless 0 < p < 1 and dof > 0.
double chi2Quantile(double p, double dof);

// Two-sided (1 - alpha) acceptance region for the ANEES of `runs_K` Monte-Carlo runs of an n-dimensional state:
// K * ANEES ~ chi2(K * n) when the filter is consistent.
struct AneesBand {
  double low;
  double high;
};

// Throws std::invalid_argument unless runs_K >= 1, state_dim >= 1 and 0 < alpha < 1.
AneesBand aneesBand(int runs_K, int state_dim, double alpha = 0.05);

}  // namespace swa::monitor

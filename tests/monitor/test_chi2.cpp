// Chi-square toolkit: reference values are 30-digit mpmath results unless marked; every algorithmic check is
// against an independent formula (closed forms, a finite Poisson sum, Simpson integration, Wilson–Hilferty), so a
// shared mistake in the incomplete gamma cannot make the implementation agree with itself.

#include "swa/monitor/chi2.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

namespace swa::monitor {
namespace {

constexpr double kPi = 3.14159265358979323846;

void expectRelNear(double actual, double expected, double rel) {
  EXPECT_NEAR(actual, expected, rel * std::fabs(expected)) << "expected " << expected;
}

// Upper tail of chi2 with even dof 2m: Q = e^(-x/2) Σ_{j<m} (x/2)^j / j!. A finite sum of positive terms, each
// formed in logs, so it is exact to rounding even at dof = 2000 and shares no code path with the gamma routines.
double evenDofUpperTail(double x, int dof) {
  const double lambda = 0.5 * x;
  double sum = 0.0;
  for (int j = 0; j < dof / 2; ++j) {
    sum += std::exp(-lambda + j * std::log(lambda) - std::lgamma(j + 1.0));
  }
  return sum;
}

// Composite Simpson on the chi2 density after t = s^2, which turns the t^(dof/2 - 1) corner at 0 into a smooth
// s^(dof - 1); used for odd and non-integer dof, which have no finite closed form.
double simpsonCdf(double x, double dof, int intervals) {
  const double a = 0.5 * dof;
  auto integrand = [a](double s) {
    if (s <= 0.0) return 0.0;
    const double t = s * s;
    const double pdf = std::exp((a - 1.0) * std::log(t) - 0.5 * t - a * std::log(2.0) - std::lgamma(a));
    return 2.0 * s * pdf;
  };
  const double upper = std::sqrt(x);
  const double h = upper / intervals;
  double sum = integrand(0.0) + integrand(upper);
  for (int i = 1; i < intervals; ++i) sum += (i % 2 == 1 ? 4.0 : 2.0) * integrand(i * h);
  return sum * h / 3.0;
}

TEST(Chi2Quantile, MatchesTableValues) {
  // GIVEN textbook quantiles (dof 2 has the closed form -2 ln(1 - p); dof 1 is the squared normal quantile)
  // WHEN each is computed THEN it agrees to 1e-10 relative, well inside the 1e-10 contract.
  expectRelNear(chi2Quantile(0.95, 2), 5.99146454710798021, 1e-10);
  expectRelNear(chi2Quantile(0.99, 2), 9.21034037197618096, 1e-10);
  expectRelNear(chi2Quantile(0.95, 2), -2.0 * std::log(0.05), 1e-12);
  expectRelNear(chi2Quantile(0.025, 24), 12.4011502174444332, 1e-10);
  expectRelNear(chi2Quantile(0.975, 24), 39.3640770266039090, 1e-10);
  expectRelNear(chi2Quantile(0.5, 1), 0.454936423119572752, 1e-10);
  expectRelNear(chi2Quantile(0.99, 4), 13.2767041359876225, 1e-10);
  expectRelNear(chi2Quantile(0.999, 3), 16.2662361962381309, 1e-10);
  expectRelNear(chi2Quantile(1e-6, 5), 0.0128961602064970966, 1e-10);
}

TEST(Chi2Quantile, LargeDofAgreesWithIndependentMethods) {
  // GIVEN dof = 2000 (a 12-run ANEES over a large swarm state is of this size)
  const double upper = chi2Quantile(0.975, 2000);
  const double lower = chi2Quantile(0.025, 2000);

  // THEN the high-precision reference holds to 1e-10 relative
  expectRelNear(upper, 2125.84230244977550, 1e-10);
  expectRelNear(lower, 1877.94603681539043, 1e-10);

  // AND the exact even-dof Poisson sum gives back the tail probabilities at the returned points
  EXPECT_NEAR(evenDofUpperTail(upper, 2000), 0.025, 1e-11);
  EXPECT_NEAR(evenDofUpperTail(lower, 2000), 0.975, 1e-11);

  // AND Wilson–Hilferty (accurate to ~1e-5 relative at this dof) agrees to 1e-4, with z_0.975 = 1.959963984540054
  const double k = 2000.0;
  const double s = std::sqrt(2.0 / (9.0 * k));
  const double z = 1.959963984540054;
  expectRelNear(upper, k * std::pow(1.0 - s * s + z * s, 3), 1e-4);
  expectRelNear(lower, k * std::pow(1.0 - s * s - z * s, 3), 1e-4);
}

TEST(Chi2Quantile, VeryLargeDofAndExtremeTails) {
  // GIVEN dof well beyond the required 10000 and probabilities far in either tail
  // THEN the references hold, and the lower tail at dof 1 follows x = (pi/2) p^2 (from P ~ sqrt(2x/pi))
  expectRelNear(chi2Quantile(0.5, 10000), 9999.33334123514483, 1e-10);
  expectRelNear(chi2Quantile(0.975, 20000), 20393.8836499997664, 1e-10);
  expectRelNear(chi2Quantile(1e-20, 1), 0.5 * kPi * 1e-40, 1e-10);
  // dof 2 upper tail is exp(-x/2): p = 1 - 1e-12 lies at x = 24 ln 10, with the error of 1 - p carried along.
  const double q = 1.0 - (1.0 - 1e-12);
  expectRelNear(chi2Quantile(1.0 - 1e-12, 2), -2.0 * std::log(q), 1e-12);
}

TEST(Chi2Cdf, MatchesClosedFormsForDof1And2AndEvenDof) {
  // GIVEN a grid of x spanning deep lower tail to deep upper tail
  const std::vector<double> xs{1e-6, 0.01, 0.3, 1.0, 2.5, 6.0, 12.4, 24.0, 39.4, 60.0, 120.0};
  for (double x : xs) {
    // THEN dof 1 is erf(sqrt(x/2)), dof 2 is 1 - exp(-x/2), dof 24 is the 12-term Poisson sum
    EXPECT_NEAR(chi2Cdf(x, 1.0), std::erf(std::sqrt(0.5 * x)), 1e-14) << "x=" << x;
    EXPECT_NEAR(chi2Cdf(x, 2.0), -std::expm1(-0.5 * x), 1e-14) << "x=" << x;
    EXPECT_NEAR(chi2Cdf(x, 24.0), 1.0 - evenDofUpperTail(x, 24), 1e-14) << "x=" << x;
  }
}

TEST(Chi2Cdf, MatchesNumericalIntegrationForOddAndFractionalDof) {
  // GIVEN dof without a finite closed form, integrated with 20000 Simpson intervals (error < 1e-10 here)
  for (double dof : {5.0, 7.5, 13.0}) {
    for (double x : {0.5, 3.0, 6.0, 15.0, 30.0}) {
      EXPECT_NEAR(chi2Cdf(x, dof), simpsonCdf(x, dof, 20000), 1e-10) << "dof=" << dof << " x=" << x;
    }
  }
  // AND one mpmath spot value for a fractional dof
  EXPECT_NEAR(chi2Cdf(6.0, 7.5), 0.404940915312034928, 1e-14);
}

TEST(Chi2Cdf, QuantileRoundTripOverGrid) {
  // GIVEN dof from 1 to 10000 and p from 1e-8 to 1 - 1e-9
  const std::vector<double> dofs{1.0, 2.0, 3.0, 7.5, 24.0, 100.0, 1000.0, 10000.0};
  const std::vector<double> ps{1e-8, 1e-3, 0.025, 0.1, 0.5, 0.9, 0.975, 0.999, 1.0 - 1e-9};
  for (double dof : dofs) {
    double previous = 0.0;
    for (double p : ps) {
      // WHEN the quantile is fed back through the CDF
      const double x = chi2Quantile(p, dof);
      const double back = chi2Cdf(x, dof);
      // THEN p comes back: relatively in the lower tail, absolutely (1e-14) in the upper tail where 1 - P is
      // all that a double can resolve; and the quantile is strictly increasing in p
      EXPECT_NEAR(back, p, std::max(1e-10 * p, 1e-14)) << "dof=" << dof << " p=" << p;
      EXPECT_GT(x, previous) << "dof=" << dof << " p=" << p;
      previous = x;
    }
  }
}

TEST(RegularizedGammaP, MatchesClosedFormsAndLimits) {
  // GIVEN shapes with closed forms: P(1, x) = 1 - e^-x, P(1/2, x) = erf(sqrt x), P(3, x) = 1 - e^-x (1 + x + x^2/2)
  for (double x : {1e-8, 0.2, 1.0, 1.9, 2.1, 5.0, 20.0, 50.0}) {
    EXPECT_NEAR(regularizedGammaP(1.0, x), -std::expm1(-x), 1e-14) << "x=" << x;
    EXPECT_NEAR(regularizedGammaP(0.5, x), std::erf(std::sqrt(x)), 1e-14) << "x=" << x;
    EXPECT_NEAR(regularizedGammaP(3.0, x), 1.0 - std::exp(-x) * (1.0 + x + 0.5 * x * x), 1e-14) << "x=" << x;
  }
  // AND the boundary values
  EXPECT_EQ(regularizedGammaP(2.0, 0.0), 0.0);
  EXPECT_EQ(regularizedGammaP(2.0, -1.0), 0.0);
  EXPECT_EQ(regularizedGammaP(2.0, std::numeric_limits<double>::infinity()), 1.0);
  // AND continuity across the series / continued-fraction switch at x = a + 1
  EXPECT_NEAR(regularizedGammaP(4.0, std::nextafter(5.0, 0.0)), regularizedGammaP(4.0, 5.0), 1e-14);
}

TEST(AneesBand, PaperBandForTwelveRunsOfTwoStates) {
  // GIVEN the paper's K = 12 Monte-Carlo runs of a 2-state error
  const AneesBand band = aneesBand(12, 2);
  // THEN [r1, r2] = [chi2_0.025(24) / 12, chi2_0.975(24) / 12] = [1.0334, 3.2803]
  expectRelNear(band.low, 12.4011502174444332 / 12.0, 1e-10);
  expectRelNear(band.high, 39.3640770266039090 / 12.0, 1e-10);
  EXPECT_NEAR(band.low, 1.0334, 1e-4);
  EXPECT_NEAR(band.high, 3.2803, 1e-4);
}

TEST(AneesBand, WiderAlphaNarrowsAndMoreRunsTighten) {
  // GIVEN the same filter judged at 90 % instead of 95 %, or with 100 runs instead of 12
  const AneesBand at95 = aneesBand(12, 2);
  const AneesBand at90 = aneesBand(12, 2, 0.10);
  const AneesBand many = aneesBand(100, 2);
  // THEN the 90 % band lies inside the 95 % one, and more runs pull the band towards n = 2
  EXPECT_GT(at90.low, at95.low);
  EXPECT_LT(at90.high, at95.high);
  expectRelNear(at90.low, chi2Quantile(0.05, 24) / 12.0, 1e-14);
  EXPECT_GT(many.low, at95.low);
  EXPECT_LT(many.high, at95.high);
  EXPECT_LT(many.low, 2.0);
  EXPECT_GT(many.high, 2.0);
}

TEST(Chi2Errors, RejectsInvalidArguments) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  // GIVEN p outside (0, 1), non-positive dof or shape, and NaN THEN each call throws std::invalid_argument
  EXPECT_THROW(chi2Quantile(0.0, 2.0), std::invalid_argument);
  EXPECT_THROW(chi2Quantile(1.0, 2.0), std::invalid_argument);
  EXPECT_THROW(chi2Quantile(-0.1, 2.0), std::invalid_argument);
  EXPECT_THROW(chi2Quantile(1.5, 2.0), std::invalid_argument);
  EXPECT_THROW(chi2Quantile(nan, 2.0), std::invalid_argument);
  EXPECT_THROW(chi2Quantile(0.5, 0.0), std::invalid_argument);
  EXPECT_THROW(chi2Quantile(0.5, -3.0), std::invalid_argument);
  EXPECT_THROW(chi2Quantile(0.5, nan), std::invalid_argument);
  EXPECT_THROW(chi2Cdf(1.0, 0.0), std::invalid_argument);
  EXPECT_THROW(chi2Cdf(nan, 2.0), std::invalid_argument);
  EXPECT_THROW(regularizedGammaP(0.0, 1.0), std::invalid_argument);
  EXPECT_THROW(regularizedGammaP(-1.0, 1.0), std::invalid_argument);
  EXPECT_THROW(aneesBand(0, 2), std::invalid_argument);
  EXPECT_THROW(aneesBand(12, 0), std::invalid_argument);
  EXPECT_THROW(aneesBand(12, 2, 0.0), std::invalid_argument);
  EXPECT_THROW(aneesBand(12, 2, 1.0), std::invalid_argument);
}

}  // namespace
}  // namespace swa::monitor

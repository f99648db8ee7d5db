// The truncated normal against Optuna 3.1's _truncnorm. The expected numbers were printed by
// tests/tune/optuna_reference.py (Debian's python3-optuna 3.1.0, /usr/bin/python3).
#include <catch2/catch.hpp>
#include <cmath>

#include "rlrun/rng.hpp"
#include "rlrun/tune/truncnorm.hpp"

using namespace rlrun::tune;

TEST_CASE("truncnorm: log Gaussian mass and log ndtr match Optuna, also deep in the tails",
          "[tune]") {
  CHECK(truncnorm::log_gauss_mass(-1.0, 2.0) == Approx(-0.20016629432446262).epsilon(1e-12));
  // 30 to 40 sigmas out: Phi underflows nowhere near, a naive log(Phi(b) - Phi(a)) gives -inf.
  CHECK(truncnorm::log_gauss_mass(-40.0, -30.0) == Approx(-454.32124395634315).epsilon(1e-12));
  CHECK(truncnorm::log_gauss_mass(30.0, 40.0) == Approx(-454.32124395634315).epsilon(1e-12));
  CHECK(truncnorm::log_gauss_mass(-3.0, -2.5) == Approx(-5.326764724079062).epsilon(1e-11));
  CHECK(truncnorm::log_gauss_mass(5.0, 9.0) == Approx(-15.064998393989118).epsilon(1e-11));
  CHECK(truncnorm::log_gauss_mass(-0.5, 0.5) == Approx(-0.9599163336956222).epsilon(1e-12));
  CHECK(truncnorm::log_gauss_mass(1.0, 1.0) == -INFINITY);

  CHECK(truncnorm::log_ndtr(-30.0) == Approx(-454.32124395634315).epsilon(1e-12));
  CHECK(truncnorm::log_ndtr(-5.0) == Approx(-15.064998393988724).epsilon(1e-12));
  CHECK(truncnorm::log_ndtr(0.3) == Approx(-0.4814101615884813).epsilon(1e-12));
  CHECK(truncnorm::log_ndtr(7.0) == Approx(-1.279812543885835e-12).epsilon(1e-9));
  // Continuous where the series takes over.
  CHECK(truncnorm::log_ndtr(-20.0 - 1e-9) == Approx(truncnorm::log_ndtr(-20.0)).epsilon(1e-8));
}

TEST_CASE("truncnorm: ppf and logpdf match Optuna", "[tune]") {
  CHECK(truncnorm::ppf(0.3, -1.0, 2.0) == Approx(-0.24240381788922666).epsilon(1e-10));
  CHECK(truncnorm::ppf(0.9, 3.0, 8.0) == Approx(3.642522275830557).epsilon(1e-10));
  CHECK(truncnorm::ppf(0.1, -9.0, -4.0) == Approx(-4.5149139391756865).epsilon(1e-10));
  CHECK(truncnorm::ppf(0.5, -35.0, -33.0) == Approx(-33.02097856906779).epsilon(1e-10));
  CHECK(truncnorm::ppf(0.0, -1.0, 2.0) == -1.0);
  CHECK(truncnorm::ppf(1.0, -1.0, 2.0) == 2.0);
  CHECK(std::isnan(truncnorm::ppf(0.5, 1.0, 1.0)));
  // No -log(scale) term, as in Optuna 3.1.
  CHECK(truncnorm::logpdf(0.7, -1.0, 2.0, 0.5, 0.25) == Approx(-1.0387722388802099).epsilon(1e-12));
  CHECK(truncnorm::logpdf(2.0, -1.0, 2.0, 0.5, 0.25) == -INFINITY);  // z = 6 > b
}

TEST_CASE("truncnorm: draws stay inside the bounds and follow the distribution", "[tune]") {
  rlrun::Rng rng(7);
  // A kernel far right of its range [0, 1]: mean 5, sigma 0.5, i.e. z in [-10, -8].
  double sum = 0;
  const int n = 4000;
  for (int i = 0; i < n; ++i) {
    const double x = truncnorm::sample(rng, -10.0, -8.0, 5.0, 0.5);
    REQUIRE(x >= 0.0);
    REQUIRE(x <= 1.0);
    sum += x;
  }
  // Mass piles up against the upper bound: E[z | z in [-10, -8]] ~ -8 - 1/8.
  CHECK(sum / n == Approx(5.0 + 0.5 * (-8.0 - 1.0 / 8.0)).margin(0.01));
  // A central one: the mean of N(0, 1) truncated to [-1, 2] is (phi(-1) - phi(2)) / mass.
  sum = 0;
  for (int i = 0; i < n; ++i) sum += truncnorm::sample(rng, -1.0, 2.0, 0.0, 1.0);
  const double phi1 = std::exp(-0.5) / std::sqrt(2 * M_PI),
               phi2 = std::exp(-2.0) / std::sqrt(2 * M_PI);
  CHECK(sum / n == Approx((phi1 - phi2) / std::exp(-0.20016629432446262)).margin(0.03));
}

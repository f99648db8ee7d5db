#include "rlrun/tune/truncnorm.hpp"

#include <cmath>
#include <limits>
#include <utility>

namespace rlrun::tune::truncnorm {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kLogSqrt2Pi = 0.91893853320467274178;  // log(sqrt(2 pi))

// log(exp(p) + exp(q)) (numpy.logaddexp).
double log_sum(double p, double q) {
  if (p == -kInf) return q;
  if (q == -kInf) return p;
  const double hi = std::max(p, q);
  return hi + std::log1p(std::exp(-std::fabs(p - q)));
}

// log(exp(p) - exp(q)) for p >= q (_log_diff).
double log_diff(double p, double q) { return p + std::log1p(-std::exp(q - p)); }

}  // namespace

double ndtr(double a) {
  // erfc keeps full relative precision in the left tail, where 0.5 + 0.5 * erf(x) cancels.
  return 0.5 * std::erfc(-a / std::sqrt(2.0));
}

double log_ndtr(double a) {
  if (a > 6) return -ndtr(-a);
  if (a > -20) return std::log(ndtr(a));
  // Phi(a) = phi(a) / (-a) * (1 - 1/a^2 + 1*3/a^4 - 1*3*5/a^6 + ...) for a -> -inf; summed
  // until a term no longer changes the total (the series is asymptotic, but at |a| >= 20 its
  // terms shrink far past double precision before they grow again).
  const double log_lhs = -0.5 * a * a - std::log(-a) - kLogSqrt2Pi;
  const double inv_a2 = 1.0 / (a * a);
  double total = 1.0, last = 0.0, numerator = 1.0, power = 1.0;
  double sign = 1.0;
  for (int i = 1; std::fabs(last - total) > std::numeric_limits<double>::epsilon(); ++i) {
    last = total;
    sign = -sign;
    power *= inv_a2;
    numerator *= 2.0 * i - 1.0;
    total += sign * numerator * power;
  }
  return log_lhs + std::log(total);
}

double log_gauss_mass(double a, double b) {
  // Work in the left tail, where log_ndtr is accurate: an interval right of 0 is mirrored.
  if (b <= 0) return log_diff(log_ndtr(b), log_ndtr(a));
  if (a > 0) return log_diff(log_ndtr(-a), log_ndtr(-b));
  // The interval holds 0: 1 - Phi(a) - Phi(-b) has no cancellation (both terms <= 1/2).
  return std::log1p(-ndtr(a) - ndtr(-b));
}

double ndtri_exp(double y) {
  // Optuna's _bisect(_log_ndtr_single, -100, 100, y): 100 halvings of [-100, 100] reach the
  // resolution of a double long before the end.
  double lo = -100.0, hi = 100.0, mid = 0.0;
  if (log_ndtr(lo) > y) std::swap(lo, hi);
  for (int i = 0; i < 100; ++i) {
    mid = 0.5 * (lo + hi);
    if (log_ndtr(mid) < y)
      lo = mid;
    else
      hi = mid;
  }
  return mid;
}

double ppf(double q, double a, double b) {
  if (a == b) return std::numeric_limits<double>::quiet_NaN();
  if (q == 0) return a;
  if (q == 1) return b;
  // Phi(x) = Phi(a) + q * (Phi(b) - Phi(a)), solved in log space from the nearer tail.
  if (a < 0) return ndtri_exp(log_sum(log_ndtr(a), std::log(q) + log_gauss_mass(a, b)));
  return -ndtri_exp(log_sum(log_ndtr(-b), std::log1p(-q) + log_gauss_mass(a, b)));
}

double logpdf(double x, double a, double b, double loc, double scale) {
  return logpdf(x, a, b, loc, scale, log_gauss_mass(a, b));
}

double logpdf(double x, double a, double b, double loc, double scale, double log_mass) {
  if (a == b) return std::numeric_limits<double>::quiet_NaN();
  const double z = (x - loc) / scale;
  if (z < a || z > b) return -kInf;
  return -0.5 * z * z - kLogSqrt2Pi - log_mass;
}

double sample(Rng& rng, double a, double b, double loc, double scale) {
  return ppf(rng.uniform(), a, b) * scale + loc;
}

}  // namespace rlrun::tune::truncnorm

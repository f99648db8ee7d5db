#pragma once
// The truncated standard normal on [a, b] as Optuna 3.1's TPE uses it
// (optuna/samplers/_tpe/_truncnorm.py, itself SciPy's truncnorm code): a log density, the log
// of the Gaussian mass between two bounds and sampling by inverse CDF. Everything works in log
// space and in the left tail (mirroring right-tail intervals), so kernels whose bounds lie many
// sigmas away from their mean (a narrow kernel near the edge of the range) give finite numbers
// instead of log(0) or 0/0.
//
// Bounds a and b are standardised: (bound - loc) / scale.
#include "rlrun/rng.hpp"

namespace rlrun::tune::truncnorm {

// Phi(a), the standard normal CDF, through erfc in both tails.
double ndtr(double a);
// log Phi(a): log(Phi(a)) down to a = -20, an asymptotic series below (_log_ndtr_single), and
// -Phi(-a) above a = 6, where log(1 - x) ~ -x.
double log_ndtr(double a);
// log(Phi(b) - Phi(a)) for a <= b (_log_gauss_mass): -inf when a == b.
double log_gauss_mass(double a, double b);
// The x with log Phi(x) = y (_ndtri_exp): bisection on [-100, 100] as Optuna does it.
double ndtri_exp(double y);
// The q-quantile of the standard normal truncated to [a, b] (ppf); NaN when a == b.
double ppf(double q, double a, double b);
// log density at x of the normal N(loc, scale^2) truncated to [loc + a*scale, loc + b*scale],
// as Optuna 3.1 computes it: the standardised density, WITHOUT the -log(scale) term. Optuna
// fixed that in 3.5 (PR #5110); rlrun matches 3.1, the version it reads and writes studies for,
// and its TPE ranks candidates by these numbers. -inf outside [a, b], NaN when a == b.
double logpdf(double x, double a, double b, double loc, double scale);
// The same with log_gauss_mass(a, b) already known (a mixture evaluates each kernel at many
// points: the mass is the costly part).
double logpdf(double x, double a, double b, double loc, double scale, double log_mass);
// One draw of that distribution: ppf of a uniform draw (rvs).
double sample(Rng& rng, double a, double b, double loc, double scale);

}  // namespace rlrun::tune::truncnorm

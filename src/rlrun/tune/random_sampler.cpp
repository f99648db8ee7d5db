#include "rlrun/tune/random_sampler.hpp"

#include <algorithm>
#include <cmath>

namespace rlrun::tune {
namespace {

// numpy.round: to the nearest integer, halves to even (std::nearbyint in the default mode).
double round_half_even(double x) { return std::nearbyint(x); }

// _untransform_numerical_param for a stepped parameter: onto the grid low + k * step, clipped.
double onto_grid(double x, double low, double high, double step) {
  return std::clamp(round_half_even((x - low) / step) * step + low, low, high);
}

// A continuous draw lands in [low, high): Optuna caps it at nextafter(high, -inf) unless the
// range is a single point. The lower clamp only guards exp(log(low)) rounding below low.
double below_high(double x, double low, double high) {
  if (low == high) return low;
  return std::clamp(x, low, std::nextafter(high, low));
}

}  // namespace

double sample_uniform(Rng& rng, const Distribution& distribution) {
  if (const auto* f = std::get_if<FloatDistribution>(&distribution)) {
    if (f->log)
      return below_high(std::exp(rng.uniform(std::log(f->low), std::log(f->high))), f->low,
                        f->high);
    if (f->step) {
      const double half = 0.5 * *f->step;
      return onto_grid(rng.uniform(f->low - half, f->high + half), f->low, f->high, *f->step);
    }
    return below_high(rng.uniform(f->low, f->high), f->low, f->high);
  }
  if (const auto* i = std::get_if<IntDistribution>(&distribution)) {
    const auto low = static_cast<double>(i->low), high = static_cast<double>(i->high);
    if (i->log) {
      // Bounds log(low - 1/2), log(high + 1/2): each integer gets the log-width of its cell.
      const double x = std::exp(rng.uniform(std::log(low - 0.5), std::log(high + 0.5)));
      return std::clamp(round_half_even(x), low, high);
    }
    const auto step = static_cast<double>(i->step);
    return onto_grid(rng.uniform(low - 0.5 * step, high + 0.5 * step), low, high, step);
  }
  // Optuna draws one uniform per choice and takes the argmax: a uniform index.
  const auto& c = std::get<CategoricalDistribution>(distribution);
  return static_cast<double>(rng.below(c.choices.size()));
}

}  // namespace rlrun::tune

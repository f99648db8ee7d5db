#include "rlrun/tune/parzen_estimator.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "rlrun/tune/truncnorm.hpp"

namespace rlrun::tune {
namespace {

constexpr double kEps = 1e-12;            // parzen_estimator.py EPS: the smallest sigma unclipped
constexpr double kSigma0Magnitude = 0.2;  // SIGMA0_MAGNITUDE, Scott's-rule factor

// _transform_to_uniform: the kernels of log parameters live in log space.
double to_kernel_space(const Distribution& d, double x) {
  return is_log_scale(d) ? std::log(x) : x;
}

// _transform_from_uniform: back to a value of the distribution, rounded onto its grid.
double from_kernel_space(const Distribution& d, double x) {
  if (const auto* f = std::get_if<FloatDistribution>(&d)) {
    // Optuna leaves exp(x) unclipped; exp(log(high)) can exceed high by an ulp, which the
    // distribution's range check would refuse, hence the clamp.
    if (f->log) return std::clamp(std::exp(x), f->low, f->high);
    if (f->step)
      return std::clamp(std::nearbyint((x - f->low) / *f->step) * *f->step + f->low, f->low,
                        f->high);
    return x;
  }
  if (const auto* i = std::get_if<IntDistribution>(&d)) {
    const auto low = static_cast<double>(i->low), high = static_cast<double>(i->high);
    if (i->log) return std::clamp(std::nearbyint(std::exp(x)), low, high);
    const auto step = static_cast<double>(i->step);
    return std::clamp(std::nearbyint((x - low) / step) * step + low, low, high);
  }
  return x;
}

// log(sum(exp(v))) without overflow; -inf when every term is -inf.
double log_sum_exp(const std::vector<double>& v) {
  const double top = *std::max_element(v.begin(), v.end());
  if (!std::isfinite(top)) return top;
  double sum = 0.0;
  for (double x : v) sum += std::exp(x - top);
  return std::log(sum) + top;
}

// numpy's RandomState.choice(n, p=weights) and _sample_from_categorical_dist: the first index
// whose cumulative probability exceeds a uniform draw (capped at the last, should rounding leave
// the cumulative sum short of the draw).
size_t draw_index(Rng& rng, const double* probabilities, size_t n) {
  double total = 0.0;
  for (size_t k = 0; k < n; ++k) total += probabilities[k];
  const double u = rng.uniform() * total;
  double cumulative = 0.0;
  for (size_t k = 0; k < n; ++k) {
    cumulative += probabilities[k];
    if (cumulative > u) return k;
  }
  return n - 1;
}

}  // namespace

std::vector<double> default_weights(int n) {
  if (n <= 0) return {};
  if (n < 25) return std::vector<double>(static_cast<size_t>(n), 1.0);
  // numpy.linspace(1/n, 1, n - 25) then 25 ones.
  const int ramp = n - 25;
  std::vector<double> w;
  w.reserve(static_cast<size_t>(n));
  const double start = 1.0 / n;
  const double step = ramp > 1 ? (1.0 - start) / (ramp - 1) : 0.0;
  for (int i = 0; i < ramp; ++i) w.push_back(i == ramp - 1 && ramp > 1 ? 1.0 : start + i * step);
  w.insert(w.end(), 25, 1.0);
  return w;
}

ParzenEstimator::ParzenEstimator(const Observations& observations, const SearchSpace& space,
                                 const ParzenEstimatorParameters& parameters)
    : parameters_(parameters) {
  if (space.empty()) throw std::invalid_argument("ParzenEstimator: an empty search space");
  n_observations_ = static_cast<int>(observations.at(space.begin()->first).size());
  const size_t n = static_cast<size_t>(n_observations_);
  // With nothing observed the prior is the whole estimator (_calculate_weights).
  with_prior_ = parameters_.consider_prior || n == 0;

  // _calculate_weights.
  std::vector<double> w = n > 0 ? parameters_.weights(n_observations_) : std::vector<double>{};
  if (w.size() < n) throw std::invalid_argument("ParzenEstimator: weights(n) returned < n values");
  w.resize(n);
  double sum = 0.0;
  for (double x : w) {
    if (!(x >= 0) || !std::isfinite(x))
      throw std::invalid_argument("ParzenEstimator: weights must be finite and >= 0");
    sum += x;
  }
  if (n > 0 && sum <= 0) throw std::invalid_argument("ParzenEstimator: weights are all zero");
  if (with_prior_) {
    w.push_back(parameters_.prior_weight);
    sum += parameters_.prior_weight;
  }
  for (double& x : w) x /= sum;
  weights_ = std::move(w);

  // _precompute_sigmas0: Scott's rule over the d parameters (categorical ones count too).
  const double d = static_cast<double>(space.size());
  const double sigma0 =
      kSigma0Magnitude * std::pow(static_cast<double>(std::max<size_t>(n, 1)), -1.0 / (d + 4.0));

  for (const auto& [name, distribution] : space) {
    const std::vector<double>& observed = observations.at(name);
    if (observed.size() != n)
      throw std::invalid_argument("ParzenEstimator: '" + name + "' has a different count");
    Dimension dim;
    dim.name = name;
    dim.distribution = distribution;
    if (std::holds_alternative<CategoricalDistribution>(distribution))
      fit_categorical(dim, observed);
    else
      fit_numerical(dim, observed, sigma0);
    dims_.push_back(std::move(dim));
  }
}

void ParzenEstimator::fit_categorical(Dimension& dim, const std::vector<double>& observed) const {
  // _calculate_categorical_params: every kernel (and the prior row) starts at
  // prior_weight / (n + 1) on each choice — prior_weight / n without the prior — its own
  // choice gets +1, and each row is normalised.
  const auto& c = std::get<CategoricalDistribution>(dim.distribution);
  dim.categorical = true;
  dim.n_choices = static_cast<int>(c.choices.size());
  const size_t k = c.choices.size();
  const size_t n = observed.size();
  const size_t rows = with_prior_ ? n + 1 : n;
  const double fill = parameters_.prior_weight / static_cast<double>(with_prior_ ? n + 1 : n);
  dim.categorical_weights.assign(rows * k, fill);
  for (size_t i = 0; i < n; ++i) {
    const double x = observed[i];
    if (!(x >= 0 && x < static_cast<double>(k)))
      throw std::invalid_argument("ParzenEstimator: '" + dim.name + "' index out of range");
    dim.categorical_weights[i * k + static_cast<size_t>(x)] += 1.0;
  }
  for (size_t r = 0; r < rows; ++r) {
    double* row = dim.categorical_weights.data() + r * k;
    const double total = std::accumulate(row, row + k, 0.0);
    for (size_t j = 0; j < k; ++j) row[j] /= total;
  }
}

void ParzenEstimator::fit_numerical(Dimension& dim, const std::vector<double>& observed,
                                    double sigma0) const {
  // _calculate_parzen_bounds: stepped and integer parameters get half a step beyond each end,
  // so that the end values own a whole grid cell; log parameters work on log(value).
  if (const auto* f = std::get_if<FloatDistribution>(&dim.distribution)) {
    if (f->log) {
      dim.low = std::log(f->low);
      dim.high = std::log(f->high);
    } else if (f->step) {
      dim.q = *f->step;
      dim.low = f->low - 0.5 * *f->step;
      dim.high = f->high + 0.5 * *f->step;
    } else {
      dim.low = f->low;
      dim.high = f->high;
    }
  } else {
    const auto& i = std::get<IntDistribution>(dim.distribution);
    if (i.log) {
      dim.low = std::log(static_cast<double>(i.low) - 0.5);
      dim.high = std::log(static_cast<double>(i.high) + 0.5);
    } else {
      dim.q = static_cast<double>(i.step);
      dim.low = static_cast<double>(i.low) - 0.5 * static_cast<double>(i.step);
      dim.high = static_cast<double>(i.high) + 0.5 * static_cast<double>(i.step);
    }
  }
  if (!(dim.low < dim.high))
    throw std::invalid_argument("ParzenEstimator: '" + dim.name + "' has a single value");

  // _calculate_numerical_params.
  const double range = dim.high - dim.low;
  dim.mus.clear();
  for (double x : observed) dim.mus.push_back(to_kernel_space(dim.distribution, x));
  if (with_prior_) dim.mus.push_back(0.5 * (dim.low + dim.high));
  const size_t m = dim.mus.size();
  dim.sigmas.assign(m, 0.0);
  if (parameters_.multivariate) {
    std::fill(dim.sigmas.begin(), dim.sigmas.end(), sigma0 * range);
  } else {
    // The larger gap to the sorted neighbours, the range's ends being neighbours of the end
    // kernels only with consider_endpoints (from 2 kernels on).
    std::vector<size_t> order(m);
    std::iota(order.begin(), order.end(), size_t{0});
    std::stable_sort(order.begin(), order.end(),
                     [&](size_t a, size_t b) { return dim.mus[a] < dim.mus[b]; });
    std::vector<double> s(m + 2);  // sorted mus with the ends
    s[0] = dim.low;
    for (size_t j = 0; j < m; ++j) s[j + 1] = dim.mus[order[j]];
    s[m + 1] = dim.high;
    std::vector<double> sorted_sigmas(m);
    for (size_t j = 0; j < m; ++j)
      sorted_sigmas[j] = std::max(s[j + 1] - s[j], s[j + 2] - s[j + 1]);
    if (!parameters_.consider_endpoints && m >= 2) {
      sorted_sigmas[0] = s[2] - s[1];
      sorted_sigmas[m - 1] = s[m] - s[m - 1];
    }
    for (size_t j = 0; j < m; ++j) dim.sigmas[order[j]] = sorted_sigmas[j];
  }
  const double max_sigma = range;
  const double min_sigma = parameters_.consider_magic_clip
                               ? range / std::min(100.0, 1.0 + static_cast<double>(m))
                               : kEps;
  for (double& sigma : dim.sigmas) sigma = std::clamp(sigma, min_sigma, max_sigma);
  if (with_prior_) dim.sigmas[m - 1] = range;  // the prior's sigma, set after the clip

  dim.log_mass.resize(m);
  for (size_t j = 0; j < m; ++j)
    dim.log_mass[j] = truncnorm::log_gauss_mass((dim.low - dim.mus[j]) / dim.sigmas[j],
                                                (dim.high - dim.mus[j]) / dim.sigmas[j]);
}

const ParzenEstimator::Dimension& ParzenEstimator::dimension(const std::string& name) const {
  for (const auto& dim : dims_)
    if (dim.name == name) return dim;
  throw std::out_of_range("ParzenEstimator: no parameter '" + name + "'");
}

Observations ParzenEstimator::sample(Rng& rng, int size) const {
  const auto count = static_cast<size_t>(std::max(size, 0));
  std::vector<size_t> active(count);
  for (auto& a : active) a = draw_index(rng, weights_.data(), weights_.size());
  Observations out;
  for (const auto& dim : dims_) {
    std::vector<double>& values = out[dim.name];
    values.resize(count);
    for (size_t s = 0; s < count; ++s) {
      const size_t k = active[s];
      if (dim.categorical) {
        const auto choices = static_cast<size_t>(dim.n_choices);
        values[s] = static_cast<double>(
            draw_index(rng, dim.categorical_weights.data() + k * choices, choices));
      } else {
        const double mu = dim.mus[k], sigma = dim.sigmas[k];
        const double x =
            truncnorm::sample(rng, (dim.low - mu) / sigma, (dim.high - mu) / sigma, mu, sigma);
        values[s] = from_kernel_space(dim.distribution, x);
      }
    }
  }
  return out;
}

std::vector<double> ParzenEstimator::log_pdf(const Observations& samples) const {
  const size_t n_samples = samples.at(dims_.front().name).size();
  const size_t n_kernels = weights_.size();
  // component[s][k] = sum over parameters of kernel k's log density at sample s.
  std::vector<std::vector<double>> component(n_samples, std::vector<double>(n_kernels, 0.0));
  for (const auto& dim : dims_) {
    const std::vector<double>& values = samples.at(dim.name);
    if (values.size() != n_samples)
      throw std::invalid_argument("ParzenEstimator::log_pdf: '" + dim.name + "' count differs");
    for (size_t s = 0; s < n_samples; ++s) {
      if (dim.categorical) {
        const auto choice = static_cast<size_t>(values[s]);
        if (!(values[s] >= 0) || choice >= static_cast<size_t>(dim.n_choices))
          throw std::invalid_argument("ParzenEstimator::log_pdf: '" + dim.name + "' index");
        for (size_t k = 0; k < n_kernels; ++k)
          component[s][k] +=
              std::log(dim.categorical_weights[k * static_cast<size_t>(dim.n_choices) + choice]);
        continue;
      }
      const double x = to_kernel_space(dim.distribution, values[s]);
      for (size_t k = 0; k < n_kernels; ++k) {
        const double mu = dim.mus[k], sigma = dim.sigmas[k];
        const double a = (dim.low - mu) / sigma, b = (dim.high - mu) / sigma;
        if (!dim.q) {
          // truncnorm.logpdf without -log(sigma), as Optuna 3.1 (truncnorm.hpp).
          component[s][k] += truncnorm::logpdf(x, a, b, mu, sigma, dim.log_mass[k]);
        } else {
          // The kernel's mass over the value's grid cell, relative to its mass in range.
          const double upper = std::min(x + 0.5 * *dim.q, dim.high);
          const double lower = std::max(x - 0.5 * *dim.q, dim.low);
          component[s][k] += truncnorm::log_gauss_mass((lower - mu) / sigma, (upper - mu) / sigma) -
                             dim.log_mass[k];
        }
      }
    }
  }
  std::vector<double> out(n_samples);
  for (size_t s = 0; s < n_samples; ++s) {
    for (size_t k = 0; k < n_kernels; ++k) component[s][k] += std::log(weights_[k]);
    out[s] = log_sum_exp(component[s]);
  }
  return out;
}

}  // namespace rlrun::tune

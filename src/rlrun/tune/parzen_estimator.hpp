#pragma once
// Optuna 3.1's _ParzenEstimator (optuna/samplers/_tpe/parzen_estimator.py): a mixture with one
// kernel per observation plus an optional prior kernel, over one or several parameters. TPE
// fits one to the good trials ("below", l(x)) and one to the rest ("above", g(x)), draws
// candidates from l and keeps the one with the largest log l(x) - log g(x).
//
// Per parameter, in the space the kernels live in (log of the value for log parameters):
//  * float/int: a normal truncated to the range, with the range widened by half a step for
//    stepped and integer parameters (their log density is then the kernel's mass over the
//    value's grid cell [x - q/2, x + q/2], not a density);
//  * categorical: a distribution over the choices, 1 on the observed choice plus
//    prior_weight / (n + 1) on every choice, normalised.
// Bandwidths: with `multivariate` every kernel of a parameter has sigma = sigma0 * (high - low)
// with Scott's rule sigma0 = 0.2 * n^(-1 / (d + 4)) (d = number of parameters, n = number of
// observations); without it, a kernel's sigma is the larger distance to its sorted neighbours
// (the range's ends counting as neighbours only with consider_endpoints). Both are clipped to
// [(high - low) / min(100, 1 + kernels), high - low] ("magic clip"); the prior kernel sits at
// the centre with sigma = high - low. A kernel's weight is weights(n)[i], the prior's
// prior_weight, normalised. The kernels of all parameters share the mixture component, so a
// multivariate estimator is a product kernel per observation.
//
// Values in and out are in the internal representation (distribution.hpp).
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "rlrun/rng.hpp"
#include "rlrun/tune/sampler.hpp"

namespace rlrun::tune {

// Parameter name -> one value per observation (or per sample), all of the same length.
using Observations = std::map<std::string, std::vector<double>>;
// n observations -> their n weights, oldest first (TPESampler's `weights` argument).
using WeightsFunction = std::function<std::vector<double>(int)>;

// Optuna's default_weights: all 1 below 25 observations; above, the 25 newest weigh 1 and the
// older ones ramp linearly from 1/n (numpy.linspace(1/n, 1, n - 25)), so old trials fade.
std::vector<double> default_weights(int n);

struct ParzenEstimatorParameters {
  bool consider_prior = true;       // add the prior kernel (always, with no observations)
  double prior_weight = 1.0;        // the prior kernel's weight; categorical smoothing mass
  bool consider_magic_clip = true;  // clip sigmas below at range / min(100, 1 + kernels)
  bool consider_endpoints = false;  // univariate: the range's ends bound the end kernels' sigma
  bool multivariate = false;        // Scott's-rule sigmas (else neighbour distances)
  WeightsFunction weights = default_weights;  // the observations' weights (oldest first)
};

class ParzenEstimator {
 public:
  // One parameter's kernels.
  struct Dimension {
    std::string name;
    Distribution distribution;
    bool categorical = false;
    double low = 0, high = 0;  // numerical: the kernels' range (log space for log params)
    std::optional<double> q;   // numerical: the grid step of stepped and (non-log) int params
    std::vector<double> mus;   // numerical: one per kernel, observations first, prior last
    std::vector<double> sigmas;
    std::vector<double> log_mass;  // numerical: log of each kernel's mass inside [low, high]
    int n_choices = 0;             // categorical: kernels x choices probabilities, row-major
    std::vector<double> categorical_weights;
  };

  // `observations` holds every parameter of `space` (a non-empty space), values in range.
  ParzenEstimator(const Observations& observations, const SearchSpace& space,
                  const ParzenEstimatorParameters& parameters);

  // `size` joint draws: a kernel by weight, then each parameter from that kernel.
  Observations sample(Rng& rng, int size) const;
  // The mixture's log density (log mass on grid parameters) at each joint sample.
  std::vector<double> log_pdf(const Observations& samples) const;

  const std::vector<double>& weights() const { return weights_; }  // one per kernel, sum 1
  const Dimension& dimension(const std::string& name) const;

 private:
  void fit_numerical(Dimension& dim, const std::vector<double>& observed, double sigma0) const;
  void fit_categorical(Dimension& dim, const std::vector<double>& observed) const;

  ParzenEstimatorParameters parameters_;
  int n_observations_ = 0;
  bool with_prior_ = true;
  std::vector<double> weights_;
  std::vector<Dimension> dims_;
};

}  // namespace rlrun::tune

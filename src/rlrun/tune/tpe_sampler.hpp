#pragma once
// Optuna 3.1's TPESampler (optuna/samplers/_tpe/sampler.py), single-objective, with the
// settings rl-zoo's hyperparameter search uses as defaults (rl_zoo3/exp_manager.py:
// TPESampler(n_startup_trials=..., seed=..., multivariate=True)).
//
// A trial's parameters come from, in this order:
//  * random sampling (RandomSampler) until n_startup_trials trials are COMPLETE or PRUNED;
//  * with `multivariate`, one joint draw over the relative search space — the parameters every
//    COMPLETE/PRUNED trial asked with the same distribution (intersection_search_space.hpp),
//    minus single-valued ones: the trials are ranked and split into the gamma(n) best
//    ("below") and the rest ("above") (observation_pairs.hpp), a ParzenEstimator is fitted to
//    each, n_ei_candidates points are drawn from the "below" one, and the candidate with the
//    largest log l(x) - log g(x) wins;
//  * the same for each parameter outside that space, on its own (sample_independent), over the
//    trials that have it — conditional parameters end up here. Optuna hands these the same
//    estimator settings, so with `multivariate` they get Scott's-rule sigmas with d = 1.
//
// Random streams: reseed(seed, trial) derives this trial's TPE stream and its random sampler's
// stream from (seed, trial number), so a trial's draws do not depend on which worker runs it
// (bit-identical numbers to numpy's streams are not a goal; the semantics are).
#include <cstdint>
#include <functional>
#include <optional>

#include "rlrun/rng.hpp"
#include "rlrun/tune/parzen_estimator.hpp"
#include "rlrun/tune/random_sampler.hpp"
#include "rlrun/tune/sampler.hpp"

namespace rlrun::tune {

// Optuna's default_gamma: the best 10 % of the trials, at most 25, form l(x).
int default_gamma(int n);

struct TpeConfig {
  bool consider_prior = true;       // a prior kernel (range centre, sigma = range) in l and g
  double prior_weight = 1.0;        // its weight; also the categorical smoothing mass
  bool consider_magic_clip = true;  // lower bound on kernel widths (parzen_estimator.hpp)
  bool consider_endpoints = false;  // univariate sigmas: the range ends count as neighbours
  int n_startup_trials = 10;        // random sampling until this many COMPLETE/PRUNED trials
  int n_ei_candidates = 24;         // candidates drawn from l(x) per sample
  std::function<int(int)> gamma = default_gamma;  // n trials -> size of the "below" set
  WeightsFunction weights = default_weights;      // n observations -> their weights
  bool multivariate = true;  // joint sampling of the relative search space (rl-zoo)
};

// One TPE step's two mixtures: l(x) over the best trials, g(x) over the rest.
struct TpeEstimators {
  ParzenEstimator below;
  ParzenEstimator above;
};

class TpeSampler final : public Sampler {
 public:
  static constexpr uint64_t kStream = 0xbb67ae8584caa73bULL;

  explicit TpeSampler(TpeConfig config = {}, uint64_t seed = 0);

  void reseed(uint64_t seed, int trial_number) override;
  SearchSpace infer_relative_search_space(const StudyView& study) override;
  std::map<std::string, double> sample_relative(const StudyView& study,
                                                const SearchSpace& space) override;
  double sample_independent(const StudyView& study, const std::string& name,
                            const Distribution& distribution) override;

  const TpeConfig& config() const { return config_; }

  // The estimators a TPE step over `space` fits to `study` (one parameter for an independent
  // step); nullopt while fewer than n_startup_trials trials are COMPLETE or PRUNED.
  std::optional<TpeEstimators> fit(const StudyView& study, const SearchSpace& space) const;

 private:
  // The TPE step over `space` (one parameter for sample_independent); empty while fewer than
  // n_startup_trials trials count.
  std::map<std::string, double> sample_tpe(const StudyView& study, const SearchSpace& space);

  TpeConfig config_;
  Rng rng_;
  RandomSampler random_;
};

}  // namespace rlrun::tune

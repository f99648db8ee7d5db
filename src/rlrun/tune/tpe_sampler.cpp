#include "rlrun/tune/tpe_sampler.hpp"

#include <cmath>
#include <limits>

#include "rlrun/core/errors.hpp"
#include "rlrun/tune/intersection_search_space.hpp"
#include "rlrun/tune/observation_pairs.hpp"

namespace rlrun::tune {

int default_gamma(int n) { return std::min(static_cast<int>(std::ceil(0.1 * n)), 25); }

TpeSampler::TpeSampler(TpeConfig config, uint64_t seed)
    : config_(std::move(config)), rng_(trial_seed(seed, 0, kStream)), random_(seed) {
  if (config_.n_startup_trials < 0) throw ConfigError("TPE: n_startup_trials must be >= 0");
  if (config_.n_ei_candidates < 1) throw ConfigError("TPE: n_ei_candidates must be >= 1");
  if (!(config_.prior_weight > 0) || !std::isfinite(config_.prior_weight))
    throw ConfigError("TPE: prior_weight must be > 0");
  if (!config_.gamma || !config_.weights) throw ConfigError("TPE: gamma and weights must be set");
}

void TpeSampler::reseed(uint64_t seed, int trial_number) {
  rng_.reseed(trial_seed(seed, trial_number, kStream));
  random_.reseed(seed, trial_number);
}

SearchSpace TpeSampler::infer_relative_search_space(const StudyView& study) {
  if (!config_.multivariate) return {};
  SearchSpace space = intersection_search_space(study.trials, /*include_pruned=*/true);
  std::erase_if(space, [](const auto& entry) { return single(entry.second); });
  return space;
}

std::map<std::string, double> TpeSampler::sample_relative(const StudyView& study,
                                                          const SearchSpace& space) {
  if (space.empty()) return {};
  return sample_tpe(study, space);
}

double TpeSampler::sample_independent(const StudyView& study, const std::string& name,
                                      const Distribution& distribution) {
  // Optuna's Trial._suggest never asks a sampler for a single-valued parameter; a direct
  // caller gets its one value rather than a degenerate estimator.
  if (single(distribution)) return sample_uniform(rng_, distribution);
  auto sampled = sample_tpe(study, SearchSpace{{name, distribution}});
  if (sampled.empty()) return random_.sample_independent(study, name, distribution);
  return sampled.at(name);
}

std::optional<TpeEstimators> TpeSampler::fit(const StudyView& study,
                                             const SearchSpace& space) const {
  const ObservationPairs pairs = get_observation_pairs(study, space);
  const int n = static_cast<int>(pairs.keys.size());
  if (n < config_.n_startup_trials) return std::nullopt;

  // The split is over every counted trial; a trial without the parameter(s) then drops out of
  // its side (Optuna's param_mask), so gamma sees the whole study, l and g only who has them.
  const BelowAbove split = split_observation_pairs(pairs.keys, config_.gamma(n));
  auto gather = [&](const std::vector<size_t>& indices) {
    Observations observed;
    for (const auto& [name, distribution] : space) observed[name];
    for (size_t i : indices) {
      bool present = true;
      for (const auto& [name, distribution] : space)
        present = present && !std::isnan(pairs.values.at(name)[i]);
      if (!present) continue;
      for (const auto& [name, distribution] : space)
        observed[name].push_back(pairs.values.at(name)[i]);
    }
    return observed;
  };
  const ParzenEstimatorParameters parameters{
      config_.consider_prior,     config_.prior_weight, config_.consider_magic_clip,
      config_.consider_endpoints, config_.multivariate, config_.weights};
  return TpeEstimators{ParzenEstimator(gather(split.below), space, parameters),
                       ParzenEstimator(gather(split.above), space, parameters)};
}

std::map<std::string, double> TpeSampler::sample_tpe(const StudyView& study,
                                                     const SearchSpace& space) {
  const std::optional<TpeEstimators> fitted = fit(study, space);
  if (!fitted) return {};
  const ParzenEstimator& below = fitted->below;
  const ParzenEstimator& above = fitted->above;
  const Observations candidates = below.sample(rng_, config_.n_ei_candidates);
  const std::vector<double> log_l = below.log_pdf(candidates);
  const std::vector<double> log_g = above.log_pdf(candidates);

  // _compare: the first candidate with the largest log l - log g (numpy.argmax).
  size_t best = 0;
  double best_score = -std::numeric_limits<double>::infinity();
  for (size_t c = 0; c < log_l.size(); ++c) {
    const double score = log_l[c] - log_g[c];
    if (score > best_score) {
      best_score = score;
      best = c;
    }
  }
  std::map<std::string, double> out;
  for (const auto& [name, values] : candidates) out[name] = values.at(best);
  return out;
}

}  // namespace rlrun::tune

#pragma once
// Optuna 3.1's RandomSampler (optuna/samplers/_random.py): every parameter drawn on its own,
// uniformly in the space Optuna's _SearchSpaceTransform builds (optuna/_transform.py) — the log
// of the range for log parameters, and for stepped ones the range widened by half a step on
// each side and rounded back onto the grid, so that the end points get as much mass as the
// inner grid points. TPESampler draws its first n_startup_trials trials with it.
#include <cstdint>

#include "rlrun/rng.hpp"
#include "rlrun/tune/sampler.hpp"

namespace rlrun::tune {

// One uniform draw from `distribution`, in the internal representation (distribution.hpp).
double sample_uniform(Rng& rng, const Distribution& distribution);

class RandomSampler final : public Sampler {
 public:
  // The stream constant that separates this sampler's draws from other samplers' of one trial.
  static constexpr uint64_t kStream = 0x6a09e667f3bcc909ULL;

  explicit RandomSampler(uint64_t seed = 0) : rng_(trial_seed(seed, 0, kStream)) {}

  void reseed(uint64_t seed, int trial_number) override {
    rng_.reseed(trial_seed(seed, trial_number, kStream));
  }
  SearchSpace infer_relative_search_space(const StudyView&) override { return {}; }
  std::map<std::string, double> sample_relative(const StudyView&, const SearchSpace&) override {
    return {};
  }
  double sample_independent(const StudyView&, const std::string&,
                            const Distribution& distribution) override {
    return sample_uniform(rng_, distribution);
  }

 private:
  Rng rng_;
};

}  // namespace rlrun::tune

#pragma once
// Studies whose parameter importances are known, for the fANOVA and report tests: the trials
// of tests/tune/optuna_importances.py, drawn with the same generator, so that Optuna's numbers
// for them (which that script prints) can stand in the tests as constants.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "rlrun/tune/distribution.hpp"
#include "rlrun/tune/frozen_trial.hpp"

namespace rlrun::tune::testing {

// Steele, Lea and Flood's SplitMix64 (the script's class of the same name).
class SplitMix64 {
 public:
  explicit SplitMix64(uint64_t seed) : state_(seed) {}
  uint64_t next() {
    state_ += 0x9E3779B97F4A7C15ULL;
    uint64_t z = state_;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
  }
  double uniform() { return static_cast<double>(next() >> 11) * (1.0 / 9007199254740992.0); }

 private:
  uint64_t state_;
};

// One trial's parameters (internal representation) and value.
struct SyntheticTrial {
  std::map<std::string, Distribution> space;
  std::map<std::string, double> params;
  double value = 0;
};

inline double log_uniform(SplitMix64& rng, double low, double high) {
  return std::exp(std::log(low) + rng.uniform() * (std::log(high) - std::log(low)));
}

inline SyntheticTrial x1_only(SplitMix64& rng) {
  SyntheticTrial t;
  for (const char* name : {"x1", "x2", "x3"}) {
    t.space[name] = FloatDistribution{0.0, 1.0, false, std::nullopt};
    t.params[name] = rng.uniform();
  }
  t.value = std::sin(3.0 * t.params["x1"]);
  return t;
}

inline SyntheticTrial x1_then_x2(SplitMix64& rng) {
  SyntheticTrial t;
  for (const char* name : {"x1", "x2", "x3"}) {
    t.space[name] = FloatDistribution{0.0, 1.0, false, std::nullopt};
    t.params[name] = rng.uniform();
  }
  t.value = t.params["x1"] + 0.3 * t.params["x2"];
  return t;
}

inline SyntheticTrial categorical(SplitMix64& rng) {
  SyntheticTrial t;
  t.space["optimizer"] = CategoricalDistribution{{"adam", "sgd", "rmsprop"}};
  t.space["x"] = FloatDistribution{-1.0, 1.0, false, std::nullopt};
  const int index = std::min(static_cast<int>(rng.uniform() * 3), 2);
  const double x = -1.0 + 2.0 * rng.uniform();
  t.params["optimizer"] = index;
  t.params["x"] = x;
  t.value = std::vector<double>{0.0, 2.0, 5.0}[static_cast<size_t>(index)] + 0.3 * x;
  return t;
}

inline SyntheticTrial log_params(SplitMix64& rng) {
  SyntheticTrial t;
  t.space["learning_rate"] = FloatDistribution{1e-5, 1e-1, true, std::nullopt};
  t.space["gamma"] = FloatDistribution{0.9, 0.9999, false, std::nullopt};
  t.space["n_epochs"] = IntDistribution{1, 20, false, 1};
  const double lr = log_uniform(rng, 1e-5, 1e-1);
  const double gamma = 0.9 + rng.uniform() * (0.9999 - 0.9);
  const int n_epochs = 1 + std::min(static_cast<int>(rng.uniform() * 20), 19);
  t.params = {{"learning_rate", lr}, {"gamma", gamma}, {"n_epochs", n_epochs}};
  t.value = -std::pow(std::log10(lr) + 3.0, 2) + 10.0 * gamma + 0.01 * n_epochs;
  return t;
}

// Optuna measures volumes in a log parameter's own units (transform_log=False).
inline SyntheticTrial log_raw_space(SplitMix64& rng) {
  SyntheticTrial t;
  t.space["learning_rate"] = FloatDistribution{1e-5, 1e-1, true, std::nullopt};
  t.space["x"] = FloatDistribution{0.0, 1.0, false, std::nullopt};
  const double lr = log_uniform(rng, 1e-5, 1e-1);
  const double x = rng.uniform();
  t.params = {{"learning_rate", lr}, {"x", x}};
  t.value = (lr < 3e-4 ? 1.0 : 0.0) + 0.3 * x;
  return t;
}

// `n` COMPLETE trials numbered from 0 (the script's build(): SplitMix64(12345), 100 trials).
inline std::vector<FrozenTrial> synthetic_study(
    const std::function<SyntheticTrial(SplitMix64&)>& draw, int n = 100, uint64_t seed = 12345) {
  SplitMix64 rng(seed);
  std::vector<FrozenTrial> trials;
  for (int i = 0; i < n; ++i) {
    const SyntheticTrial s = draw(rng);
    FrozenTrial t;
    t.trial_id = i;
    t.number = i;
    t.state = TrialState::kComplete;
    t.params = s.params;
    t.distributions = s.space;
    t.values = std::vector<double>{s.value};
    trials.push_back(std::move(t));
  }
  return trials;
}

}  // namespace rlrun::tune::testing

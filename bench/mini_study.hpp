#pragma once
// A minimal in-memory study for the sampler benchmark (bench/tpe_bench.cpp) and the sampler
// tests: Optuna's ask / suggest / tell (optuna/study/study.py ask and tell,
// optuna/trial/_trial.py _suggest) with no storage, pruner or workers. The real study loop is
// rlrun's tune runtime; this one exists so that the samplers can be measured on their own.
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "rlrun/tune/sampler.hpp"

namespace rlrun::tune {

class MiniStudy {
 public:
  MiniStudy(Sampler& sampler, uint64_t seed, StudyDirection direction = StudyDirection::kMinimize)
      : sampler_(sampler), seed_(seed), direction_(direction) {}

  // A new RUNNING trial: the sampler is reseeded for it and draws the relative parameters.
  void ask() {
    FrozenTrial trial;
    trial.number = static_cast<int>(trials_.size());
    trial.trial_id = trial.number;
    trial.state = TrialState::kRunning;
    trials_.push_back(std::move(trial));
    sampler_.reseed(seed_, trials_.back().number);
    relative_space_ = sampler_.infer_relative_search_space(view());
    relative_params_ = sampler_.sample_relative(view(), relative_space_);
  }

  // Trial._suggest: the recorded value if asked before, the only value of a single-valued
  // distribution, the relative value if the relative space had this distribution and the value
  // fits, else an independent draw. Internal representation.
  double suggest(const std::string& name, const Distribution& distribution) {
    FrozenTrial& trial = trials_.back();
    if (auto found = trial.params.find(name); found != trial.params.end()) return found->second;
    double value = 0;
    auto relative = relative_params_.find(name);
    if (single(distribution)) {
      if (const auto* f = std::get_if<FloatDistribution>(&distribution))
        value = f->low;
      else if (const auto* i = std::get_if<IntDistribution>(&distribution))
        value = static_cast<double>(i->low);
    } else if (relative != relative_params_.end() && relative_space_.count(name) &&
               compatible(relative_space_.at(name), distribution) &&
               contains(distribution, relative->second)) {
      value = relative->second;
    } else {
      value = sampler_.sample_independent(view(), name, distribution);
    }
    trials_.back().params[name] = value;
    trials_.back().distributions[name] = distribution;
    return value;
  }

  void report(int64_t step, double value) { trials_.back().intermediate_values[step] = value; }

  void tell(double value, TrialState state = TrialState::kComplete) {
    FrozenTrial& trial = trials_.back();
    trial.state = state;
    if (state == TrialState::kComplete) trial.values = std::vector<double>{value};
  }

  const std::vector<FrozenTrial>& trials() const { return trials_; }
  const SearchSpace& relative_space() const { return relative_space_; }
  StudyView view() const { return StudyView{direction_, trials_}; }

 private:
  Sampler& sampler_;
  uint64_t seed_;
  StudyDirection direction_;
  std::vector<FrozenTrial> trials_;
  SearchSpace relative_space_;
  std::map<std::string, double> relative_params_;
};

}  // namespace rlrun::tune

#include "rlrun/tune/trial.hpp"

#include "rlrun/core/errors.hpp"

namespace rlrun::tune {

Trial::Trial(JournalStorage& storage, int64_t study_id, int64_t trial_id, Sampler& sampler,
             StudyDirection direction, uint64_t seed)
    : storage_(storage),
      study_id_(study_id),
      trial_id_(trial_id),
      sampler_(sampler),
      direction_(direction) {
  storage_.sync();
  const FrozenTrial& self = storage_.state().trial(trial_id_);
  number_ = self.number;
  auto fixed = self.system_attrs.find("fixed_params");
  if (fixed != self.system_attrs.end() && fixed->is_object()) fixed_params_ = *fixed;
  sampler_.reseed(seed, number_);
  const std::vector<FrozenTrial> trials = storage_.state().trials(study_id_);
  const StudyView view{direction_, trials};
  relative_space_ = sampler_.infer_relative_search_space(view);
  relative_params_ = sampler_.sample_relative(view, relative_space_);
}

nlohmann::json Trial::suggest(const std::string& name, const Distribution& distribution) {
  const FrozenTrial& self = storage_.state().trial(trial_id_);
  // Asked twice (a space that reads a parameter again): the value it already has.
  if (auto it = self.params.find(name); it != self.params.end()) {
    if (!compatible(self.distributions.at(name), distribution))
      throw RuntimeFailure("parameter '" + name + "' asked for with two different distributions");
    return to_external(distribution, it->second);
  }
  double internal = 0;
  if (fixed_params_.contains(name)) {
    // Optuna's _is_fixed_param: the enqueued value. Optuna takes one outside the range with a
    // warning; rlrun refuses it (the trial fails): the journal may come from anyone, and a value
    // far outside an int parameter's range has no int value.
    try {
      internal = to_internal(distribution, fixed_params_[name]);
    } catch (const ConfigError& e) {
      throw RuntimeFailure("trial " + std::to_string(number_) + ": fixed parameter '" + name +
                           "' = " + fixed_params_[name].dump() +
                           " does not fit its distribution: " + e.what());
    }
    if (!contains(distribution, internal))
      throw RuntimeFailure("trial " + std::to_string(number_) + ": fixed parameter '" + name +
                           "' = " + fixed_params_[name].dump() + " is outside its range");
  } else if (single(distribution)) {
    internal = std::visit(
        [](const auto& d) -> double {
          using D = std::decay_t<decltype(d)>;
          if constexpr (std::is_same_v<D, CategoricalDistribution>)
            return 0.0;
          else
            return static_cast<double>(d.low);
        },
        distribution);
  } else if (auto r = relative_params_.find(name); r != relative_params_.end() &&
                                                   relative_space_.count(name) &&
                                                   relative_space_.at(name) == distribution) {
    internal = r->second;
  } else {
    const std::vector<FrozenTrial> trials = storage_.state().trials(study_id_);
    internal = sampler_.sample_independent(StudyView{direction_, trials}, name, distribution);
  }
  storage_.set_trial_param(trial_id_, name, internal, distribution);
  return to_external(distribution, internal);
}

void Trial::set_user_attr(const std::string& key, const nlohmann::json& value) {
  storage_.set_trial_user_attr(trial_id_, key, value);
}

nlohmann::json Trial::params() const { return storage_.state().trial(trial_id_).external_params(); }

}  // namespace rlrun::tune

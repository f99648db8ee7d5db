#pragma once
// One trial as the objective sees it: Optuna's Trial (optuna/trial/_trial.py) over rlrun's
// journal storage. At its start the sampler draws the jointly sampled ("relative") parameters
// from the study's trials so far; each suggest() then takes, in Optuna's order, a fixed value
// (an enqueued or re-queued trial's "fixed_params"), the relative value, or an independent
// sample, and writes the parameter to the journal at once (as Optuna does), so a trial killed
// mid-way still shows what it was trying.
#include <cstdint>
#include <map>
#include <string>

#include "rlrun/tune/journal_storage.hpp"
#include "rlrun/tune/sampler.hpp"
#include "rlrun/tune/search_space.hpp"

namespace rlrun::tune {

class Trial : public TrialSuggest {
 public:
  // The trial must be RUNNING and owned by this worker. `seed`: the study's sampler seed.
  Trial(JournalStorage& storage, int64_t study_id, int64_t trial_id, Sampler& sampler,
        StudyDirection direction, uint64_t seed);

  nlohmann::json suggest(const std::string& name, const Distribution& distribution) override;
  void set_user_attr(const std::string& key, const nlohmann::json& value) override;

  int64_t id() const { return trial_id_; }
  int number() const { return number_; }
  // The parameters suggested so far ({name: external value}).
  nlohmann::json params() const;

 private:
  JournalStorage& storage_;
  int64_t study_id_;
  int64_t trial_id_;
  int number_ = 0;
  Sampler& sampler_;
  StudyDirection direction_;
  SearchSpace relative_space_;
  std::map<std::string, double> relative_params_;
  nlohmann::json fixed_params_ = nlohmann::json::object();
};

}  // namespace rlrun::tune

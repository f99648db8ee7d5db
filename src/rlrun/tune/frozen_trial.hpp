#pragma once
// A trial as Optuna's storages hand it to samplers and pruners (optuna/trial/_frozen.py,
// _state.py; optuna/study/_study_direction.py), and a read-only view of a study's trials. The
// numbers of the enums are Optuna's: they are written as such into the journal file.
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "rlrun/tune/distribution.hpp"

namespace rlrun::tune {

enum class TrialState : int { kRunning = 0, kComplete = 1, kPruned = 2, kFail = 3, kWaiting = 4 };
enum class StudyDirection : int { kNotSet = 0, kMinimize = 1, kMaximize = 2 };

inline bool is_finished(TrialState state) {
  return state == TrialState::kComplete || state == TrialState::kPruned ||
         state == TrialState::kFail;
}
const char* state_name(TrialState state);  // "RUNNING", "COMPLETE", ... (Optuna's names)

struct FrozenTrial {
  int64_t trial_id = 0;  // over the whole journal (all studies)
  int number = 0;        // within its study, from 0
  TrialState state = TrialState::kRunning;
  std::map<std::string, double> params;  // internal representation (distribution.hpp)
  std::map<std::string, Distribution> distributions;
  std::map<int64_t, double> intermediate_values;  // step -> value (trial.report)
  std::optional<std::vector<double>> values;      // one per objective once complete
  nlohmann::json user_attrs = nlohmann::json::object();
  nlohmann::json system_attrs = nlohmann::json::object();
  std::string datetime_start;  // ISO 8601 as Optuna writes it; empty when not set
  std::string datetime_complete;

  // Optuna's FrozenTrial.last_step: the largest reported step.
  std::optional<int64_t> last_step() const {
    if (intermediate_values.empty()) return std::nullopt;
    return intermediate_values.rbegin()->first;
  }
  // A single-objective trial's value (values[0]).
  std::optional<double> value() const {
    if (!values || values->empty()) return std::nullopt;
    return (*values)[0];
  }
  // The external value of a parameter (what Optuna's trial.params shows).
  nlohmann::json param(const std::string& name) const {
    return to_external(distributions.at(name), params.at(name));
  }
  // Every parameter's external value ({name: value}, Optuna's trial.params).
  nlohmann::json external_params() const {
    nlohmann::json out = nlohmann::json::object();
    for (const auto& [name, internal] : params)
      out[name] = to_external(distributions.at(name), internal);
    return out;
  }
};

// Optuna's study.best_trial: the first COMPLETE trial with the best value; null when none.
inline const FrozenTrial* best_trial(const std::vector<FrozenTrial>& trials,
                                     StudyDirection direction) {
  const FrozenTrial* best = nullptr;
  for (const FrozenTrial& t : trials) {
    if (t.state != TrialState::kComplete || !t.value()) continue;
    if (!best || (direction == StudyDirection::kMaximize ? *t.value() > *best->value()
                                                         : *t.value() < *best->value()))
      best = &t;
  }
  return best;
}

// What samplers and pruners see of a study: its direction and every trial in number order.
struct StudyView {
  StudyDirection direction = StudyDirection::kMinimize;
  const std::vector<FrozenTrial>& trials;
};

}  // namespace rlrun::tune

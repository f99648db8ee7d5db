#pragma once
// `rlrun tune report`: what a study holds, read from its journal (whoever wrote it: rlrun or
// Optuna) — the trials by state, the best trials with their parameters, the parameters'
// importances (fANOVA, Optuna's default evaluator: tune/fanova.hpp) and the optimisation history
// plot (Optuna's plot_optimization_history: every trial's value and the best so far, drawn with
// Cairo like `rlrun plot`).
#include <cstdint>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "rlrun/tune/frozen_trial.hpp"

namespace rlrun::tune {

struct ReportOptions {
  int top = 10;              // best trials listed
  std::string plot_path;     // the history plot (.png or .svg); empty: none
  bool plot_pruned = false;  // also mark PRUNED trials (at their last report) in the plot
  uint64_t seed = 0;         // the importance evaluator's random forest
};

// Prints the report of the study `name` whose trials are `trials` (number order).
void print_study_report(const std::string& name, StudyDirection direction,
                        const std::vector<FrozenTrial>& trials, const ReportOptions& options,
                        std::ostream& out);

// Optuna's get_param_importances(study) with its default FanovaImportanceEvaluator: over the
// COMPLETE trials, the parameters all of them share; normalised to sum to 1, largest first.
// Empty when fewer than two such trials have a finite value, no parameter varies or every value
// is the same (where Optuna raises).
std::vector<std::pair<std::string, double>> param_importances(
    const std::vector<FrozenTrial>& trials, uint64_t seed = 0);

// Optuna's plot_optimization_history: objective value per trial number (COMPLETE trials) and the
// best value so far, as a PNG or SVG (by the extension). Optuna shows COMPLETE trials only;
// `show_pruned` adds PRUNED ones, lighter, at their last reported value. Throws UsageError for
// another extension, RuntimeFailure when the file cannot be written.
void write_history_plot(const std::string& name, StudyDirection direction,
                        const std::vector<FrozenTrial>& trials, const std::string& path,
                        bool show_pruned = false);

}  // namespace rlrun::tune

#include "rlrun/tune/tune_worker.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <numeric>

#include "rlrun/core/dir_handle.hpp"
#include "rlrun/core/errors.hpp"
#include "rlrun/core/interrupt.hpp"
#include "rlrun/runtime/experiment/experiment.hpp"
#include "rlrun/runtime/io/run_results.hpp"
#include "rlrun/runtime/run/trainer.hpp"
#include "rlrun/tune/journal_storage.hpp"
#include "rlrun/tune/make_sampler.hpp"
#include "rlrun/tune/trial.hpp"
#include "rlrun/tune/worker_liveness.hpp"

namespace rlrun::tune {

namespace fs = std::filesystem;
using json = nlohmann::json;

int counted_trials(const std::vector<FrozenTrial>& trials) {
  int n = 0;
  for (const FrozenTrial& t : trials) {
    const bool requeued = t.state == TrialState::kFail && t.system_attrs.contains("rlrun:requeued");
    if (!requeued) ++n;
  }
  return n;
}

namespace {

// The console while a trial trains: each seed's training output (its tables and evaluation lines,
// all of which its log.txt keeps) goes to /dev/null unless the worker is verbose, so that a
// worker prints one line per trial event. std::cout itself stays on the terminal.
class QuietTraining {
 public:
  explicit QuietTraining(bool quiet) {
    if (!quiet) return;
    std::cout.flush();
    std::fflush(stdout);
    saved_ = ::dup(STDOUT_FILENO);
    const int null = ::open("/dev/null", O_WRONLY | O_CLOEXEC);
    if (saved_ < 0 || null < 0 || ::dup2(null, STDOUT_FILENO) < 0) {
      if (null >= 0) ::close(null);
      restore();
      return;
    }
    ::close(null);
  }
  ~QuietTraining() { restore(); }
  QuietTraining(const QuietTraining&) = delete;
  QuietTraining& operator=(const QuietTraining&) = delete;

 private:
  void restore() {
    if (saved_ < 0) return;
    std::fflush(stdout);
    ::dup2(saved_, STDOUT_FILENO);
    ::close(saved_);
    saved_ = -1;
  }
  int saved_ = -1;
};

// Marks a RUNNING trial failed and enqueues its parameters again (its fixed parameters, if it
// was itself a re-queued one, are kept: the parameters it had not reached yet).
void requeue(JournalStorage& storage, int64_t study_id, const FrozenTrial& t,
             const std::string& why) {
  json fixed = t.external_params();
  if (auto f = t.system_attrs.find("fixed_params"); f != t.system_attrs.end() && f->is_object())
    for (auto it = f->begin(); it != f->end(); ++it)
      if (!fixed.contains(it.key())) fixed[it.key()] = it.value();
  storage.set_trial_system_attr(t.trial_id, "rlrun:requeued", true);
  storage.set_trial_system_attr(t.trial_id, "fail_reason", why);
  storage.set_trial_state(t.trial_id, TrialState::kFail);
  storage.enqueue_trial(study_id, fixed, {{"rlrun:retry_of", t.number}});
}

// Under the lock: step 1-3 of the header. The trial id taken, or -1 when the study is done.
int64_t take_trial(JournalStorage& storage, int64_t study_id, const StudyConfig& study) {
  JournalStorage::Transaction transaction(storage);
  for (const FrozenTrial& t : storage.state().trials(study_id)) {
    if (t.state != TrialState::kRunning || t.trial_id == storage.state().owned_trial()) continue;
    auto worker = t.system_attrs.find("rlrun:worker");
    if (worker == t.system_attrs.end() || worker_alive(*worker, study.storage)) continue;
    std::cout << "rlrun tune: trial " << t.number << "'s worker is gone; re-queued" << std::endl;
    requeue(storage, study_id, t, "its worker stopped (killed or lost) while it ran");
  }
  int64_t taken = -1;
  for (const FrozenTrial& t : storage.state().trials(study_id))
    if (t.state == TrialState::kWaiting && storage.claim_waiting_trial(t.trial_id)) {
      taken = t.trial_id;
      break;
    }
  if (taken < 0 && counted_trials(storage.state().trials(study_id)) < study.n_trials)
    taken = storage.create_running_trial(study_id);
  if (taken >= 0)
    storage.set_trial_system_attr(taken, "rlrun:worker", this_worker(storage.worker_id()));
  return taken;
}

double reduce(const std::vector<double>& values, const std::string& how, bool maximize) {
  std::vector<double> finite;
  for (double v : values)
    if (std::isfinite(v)) finite.push_back(v);
  if (finite.empty()) return std::nan("");
  if (how == "last") return finite.back();
  if (how == "best")
    return maximize ? *std::max_element(finite.begin(), finite.end())
                    : *std::min_element(finite.begin(), finite.end());
  return std::accumulate(finite.begin(), finite.end(), 0.0) / static_cast<double>(finite.size());
}

struct TrialResult {
  TrialState state = TrialState::kComplete;
  std::optional<double> value;
  std::string fail_reason;
  bool interrupted = false;
};

class TrialRunner {
 public:
  TrialRunner(const StudyConfig& study, Registry& registry, const ExecutionContext& execution,
              JournalStorage& storage, int64_t study_id, Pruner& pruner, bool verbose)
      : study_(study),
        registry_(registry),
        execution_(execution),
        storage_(storage),
        study_id_(study_id),
        pruner_(pruner),
        verbose_(verbose) {}

  TrialResult run(Trial& trial) {
    TrialResult result;
    std::vector<Override> params;
    try {
      params = study_.space->sample(trial);
    } catch (const std::exception& e) {
      return fail("sampling failed: " + std::string(e.what()));
    }
    json overrides = json::array();
    for (const Override& o : params) overrides.push_back(o.assignment());
    storage_.set_trial_system_attr(trial.id(), "rlrun:overrides", overrides);
    const int64_t eval_freq = std::max<int64_t>(study_.n_timesteps / study_.n_evaluations, 1);
    const int64_t evals_per_seed = study_.n_timesteps / eval_freq;
    std::vector<double> seed_values;
    for (int s = 0; s < study_.seeds_per_trial; ++s) {
      Experiment experiment;
      try {
        experiment = load_experiment(study_.base, study_.seed_overrides(params, trial.number(), s),
                                     registry_);
      } catch (const ConfigError& e) {
        return fail(std::string("the sampled configuration is not valid: ") + e.what());
      }
      std::vector<double> column;      // the objective's column, from this seed's evaluations
      bool evaluation_metric = false;  // the metric is an evaluations.csv column
      int64_t k = 0;
      bool pruned = false;
      auto on_evaluation = [&](const EvaluationRow& row) -> std::string {
        ++k;
        double value = std::nan("");
        if (auto it = row.values.find(study_.objective.metric); it != row.values.end()) {
          value = it->second;
          evaluation_metric = true;
        } else {
          value = progress_value(experiment);  // its latest progress.csv value
        }
        column.push_back(value);
        if (k > evals_per_seed || !std::isfinite(value)) return "";
        const int64_t step = s * evals_per_seed + k;
        if (!report_and_ask_pruner(trial, step, value)) return "";
        pruned = true;
        return "pruned by the " + study_.pruner.type + " pruner at step " + std::to_string(step);
      };
      TrainOutcome outcome;
      try {
        QuietTraining quiet(!verbose_);
        outcome = train_experiment(experiment, registry_, execution_, {}, on_evaluation);
      } catch (const ConfigError& e) {
        return fail(std::string("the sampled configuration is not valid: ") + e.what());
      } catch (const std::exception& e) {
        return fail(std::string("training failed: ") + e.what());
      }
      if (outcome.interrupted) {
        result.interrupted = true;
        return result;
      }
      if (pruned) {
        result.state = TrialState::kPruned;
        const FrozenTrial& self = storage_.state().trial(trial.id());
        if (self.last_step()) result.value = self.intermediate_values.at(*self.last_step());
        return result;
      }
      if (!evaluation_metric) column = progress_column(experiment);
      const double value = reduce(column, study_.objective.reduce, study_.maximize());
      if (!std::isfinite(value))
        return fail("seed " + std::to_string(experiment.run.seed) + " gave no finite " +
                    study_.objective.metric +
                    " (is it a column of evaluations.csv or progress.csv?)");
      seed_values.push_back(value);
      storage_.set_trial_user_attr(trial.id(), "rlrun:seed_values", seed_values);
    }
    result.value = std::accumulate(seed_values.begin(), seed_values.end(), 0.0) /
                   static_cast<double>(seed_values.size());
    return result;
  }

 private:
  // Reports an intermediate value to the journal; true when the pruner stops the trial there.
  bool report_and_ask_pruner(const Trial& trial, int64_t step, double value) {
    storage_.report(trial.id(), step, value);
    const std::vector<FrozenTrial> trials = storage_.state().trials(study_id_);
    const FrozenTrial& self = storage_.state().trial(trial.id());
    return pruner_.prune(StudyView{direction(), trials}, self,
                         [&](const std::string& key, const json& v) {
                           storage_.set_trial_system_attr(trial.id(), key, v);
                         });
  }
  StudyDirection direction() const {
    return study_.maximize() ? StudyDirection::kMaximize : StudyDirection::kMinimize;
  }
  static TrialResult fail(const std::string& why) {
    TrialResult r;
    r.state = TrialState::kFail;
    r.fail_reason = why;
    return r;
  }
  std::string run_dir(const Experiment& e) const {
    return (fs::path(e.run.out_dir) / e.run.name / ("seed" + std::to_string(e.run.seed))).string();
  }
  std::vector<double> progress_column(const Experiment& e) const {
    try {
      const RunResult r = read_run(run_dir(e));
      auto it = r.progress.find(study_.objective.metric);
      if (it != r.progress.end()) return it->second;
    } catch (const std::exception&) {
    }
    return {};
  }
  double progress_value(const Experiment& e) const {
    const std::vector<double> column = progress_column(e);
    for (auto it = column.rbegin(); it != column.rend(); ++it)
      if (!std::isnan(*it)) return *it;
    return std::nan("");
  }

  const StudyConfig& study_;
  Registry& registry_;
  const ExecutionContext execution_;
  JournalStorage& storage_;
  int64_t study_id_;
  Pruner& pruner_;
  bool verbose_;
};

}  // namespace

WorkerSummary run_worker(const StudyConfig& study, Registry& registry,
                         const ExecutionContext& execution, bool verbose) {
  install_interrupt_handlers();
  fs::create_directories(fs::path(study.storage).parent_path());
  // The trials' run directories go to <out_dir>/trials (study_config.hpp): inside the study,
  // which may come from anyone, so not through a link (core/dir_handle.hpp).
  fs::create_directories(study.out_dir);
  DirHandle::open(study.out_dir, DirHandle::LastLink::kFollow).make_subdir("trials");
  JournalStorage storage(study.storage);
  const StudyDirection direction =
      study.maximize() ? StudyDirection::kMaximize : StudyDirection::kMinimize;
  const int64_t study_id = storage.create_or_load_study(study.name, direction);
  {
    JournalStorage::Transaction transaction(storage);
    const json& attrs = storage.state().study(study_id).user_attrs;
    if (!attrs.contains("rlrun:study_file")) {
      storage.set_study_user_attr(study_id, "rlrun:study_file", study.source);
      storage.set_study_user_attr(study_id, "rlrun:space", study.space->describe());
    }
  }
  Heartbeat heartbeat(study.storage, storage.worker_id());
  std::unique_ptr<Sampler> sampler = make_sampler(study.sampler);
  std::unique_ptr<Pruner> pruner = make_pruner(study.pruner, study.n_evaluations / 3);
  TrialRunner runner(study, registry, execution, storage, study_id, *pruner, verbose);
  WorkerSummary summary;
  const auto start = std::chrono::steady_clock::now();
  for (;;) {
    if (interrupt_requested()) {
      summary.interrupted = true;
      break;
    }
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (study.timeout && elapsed >= *study.timeout) break;
    const int64_t trial_id = take_trial(storage, study_id, study);
    if (trial_id < 0) break;
    TrialResult result;
    int number = storage.state().trial(trial_id).number;
    const auto trial_start = std::chrono::steady_clock::now();
    try {
      Trial trial(storage, study_id, trial_id, *sampler, direction, *study.sampler.seed);
      number = trial.number();
      std::cout << "rlrun tune: trial " << number << " of study '" << study.name << "'"
                << std::endl;
      result = runner.run(trial);
    } catch (const std::exception& e) {
      result.state = TrialState::kFail;
      result.fail_reason = e.what();
    }
    if (result.interrupted || interrupt_requested()) {
      storage.sync();
      requeue(storage, study_id, storage.state().trial(trial_id),
              "interrupted (Ctrl-C); re-queued");
      std::cout << "rlrun tune: trial " << number << " interrupted and re-queued" << std::endl;
      summary.interrupted = true;
      break;
    }
    if (result.state == TrialState::kFail) {
      storage.set_trial_system_attr(trial_id, "fail_reason", result.fail_reason);
      storage.set_trial_state(trial_id, TrialState::kFail);
      ++summary.failed;
      std::cout << "rlrun tune: trial " << number << " failed: " << result.fail_reason << std::endl;
    } else {
      storage.set_trial_state(trial_id, result.state, result.value);
      ++(result.state == TrialState::kPruned ? summary.pruned : summary.complete);
      const FrozenTrial& done = storage.state().trial(trial_id);
      char line[160];
      std::snprintf(
          line, sizeof line, "rlrun tune: trial %d %s: %s = %.6g (%.1f s)", number,
          result.state == TrialState::kPruned
              ? ("pruned at step " + std::to_string(done.last_step().value_or(0))).c_str()
              : "complete",
          study.objective.metric.c_str(), result.value.value_or(std::nan("")),
          std::chrono::duration<double>(std::chrono::steady_clock::now() - trial_start).count());
      std::cout << line << std::endl;
    }
  }
  return summary;
}

}  // namespace rlrun::tune

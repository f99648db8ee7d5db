#include "rlrun/runtime/run/eval_callback.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "rlrun/core/config_node.hpp"
#include "rlrun/core/errors.hpp"
#include "rlrun/core/plural.hpp"
#include "rlrun/runtime/experiment/env_factory.hpp"
#include "rlrun/runtime/experiment/env_statistics.hpp"
#include "rlrun/runtime/io/log_sinks.hpp"
#include "rlrun/runtime/run/evaluator.hpp"

namespace rlrun {

EvalCallback::EvalCallback(TrainingContext& context, const EvalConfig& config)
    : context_(context),
      config_(config),
      env_(make_env(context.env_spec, context.registry, "", unix_time_now())),
      next_(config.freq) {
  set_statistics_training(*env_, false);
  std::vector<std::string> columns = {"mean_reward", "mean_ep_length"};
  for (const std::string& key : episode_info_keywords(context.env_spec, context.registry, *env_)) {
    if (key == "is_success") {
      columns.push_back("success_rate");
    } else {
      metric_keys_.push_back(key);
      columns.push_back(key);
    }
  }
  // Checked before the first step, so a misspelt metric costs no training.
  if (std::find(columns.begin(), columns.end(), config_.best_metric) == columns.end()) {
    std::string known;
    for (const std::string& c : columns) known += (known.empty() ? "" : ", ") + c;
    const std::string where =
        config_.best_metric_where.empty() ? "" : config_.best_metric_where + ": ";
    throw ConfigError(where + "eval.best_metric: '" + config_.best_metric +
                      "' is not a column of " + "evaluations.csv for this env" +
                      did_you_mean(config_.best_metric, columns) + "; its columns: " + known);
  }
  const std::string path = context.run_dir + "/evaluations.csv";
  csv_ = CheckedFile::run_file(
      path, context.resuming ? CheckedFile::Mode::kAppend : CheckedFile::Mode::kTruncate);
  if (!context.resuming) {
    csv_ << "timesteps,mean_reward,std_reward,mean_ep_length,success_rate";
    for (const std::string& key : metric_keys_) csv_ << ',' << key;
    csv_ << '\n';
  }
  csv_.flush();
}

namespace {

// The mean of metric `key` over the episodes that reported it (NaN when none did).
double mean_metric(const EvalResult& r, const std::string& key) {
  const auto it = std::find(r.metric_keys.begin(), r.metric_keys.end(), key);
  if (it == r.metric_keys.end()) return std::nan("");
  const size_t k = static_cast<size_t>(it - r.metric_keys.begin());
  double sum = 0;
  int n = 0;
  for (const auto& episode : r.metrics)
    if (!std::isnan(episode[k])) {
      sum += episode[k];
      ++n;
    }
  return n ? sum / n : std::nan("");
}

}  // namespace

void EvalCallback::write_state(StateWriter& out) const {
  out.put_int("next", next_);
  out.put_int("evaluations", evaluations_);
  out.put_double("best", best_);
  out.put_double("best_score", best_score_);
  out.put_double("last_best", last_best_);
  out.put_int("no_improvement_evals", no_improvement_evals_);
}

void EvalCallback::read_state(const StateReader& in) {
  // Counters from an untrusted checkpoint: a negative `next` would make crossed() count up
  // from it for ever.
  next_ = in.get_count("next");
  evaluations_ = static_cast<int>(in.get_count("evaluations", INT_MAX));
  best_ = in.get_double("best");
  // Checkpoints written before best_metric existed chose on the mean reward.
  best_score_ = in.has("best_score") ? in.get_double("best_score") : best_;
  last_best_ = in.get_double("last_best");
  no_improvement_evals_ = static_cast<int>(in.get_count("no_improvement_evals", INT_MAX));
}

bool EvalCallback::on_step(int64_t num_timesteps) {
  if (!crossed(num_timesteps, config_.freq, next_)) return true;
  // SB3 sync_envs_normalization: the eval env normalises with the training statistics.
  TensorMap statistics;
  save_model_statistics(context_.env.env(0), statistics);
  load_model_statistics(*env_, statistics, /*training=*/false);
  // A separate seed stream: the training envs use seed .. seed + n_envs - 1.
  const uint64_t seed = context_.seed + static_cast<uint64_t>(context_.env_spec.section.n_envs) +
                        static_cast<uint64_t>(evaluations_++);
  const EvalResult r =
      evaluate_policy(context_.algorithm, *env_, config_.n_episodes, config_.deterministic, seed);
  double success = std::nan("");
  if (!r.successes.empty()) {
    success = 0;
    for (double s : r.successes) success += s;
    success /= static_cast<double>(r.successes.size());
  }
  char line[256];
  std::snprintf(line, sizeof line, "%lld,%.6g,%.6g,%.6g,", static_cast<long long>(num_timesteps),
                r.mean_return(), r.std_return(), r.mean_length());
  csv_ << line;
  if (!std::isnan(success)) {
    std::snprintf(line, sizeof line, "%g", success);  // as std::ostream writes a double
    csv_ << line;
  }
  std::vector<double> metric_means;
  for (const std::string& key : metric_keys_) {
    metric_means.push_back(mean_metric(r, key));
    csv_ << ',';
    if (!std::isnan(metric_means.back())) {
      std::snprintf(line, sizeof line, "%.6g", metric_means.back());
      csv_ << line;
    }
  }
  csv_ << '\n';
  csv_.flush();  // a full disk stops the run: RuntimeFailure naming the file and errno
  // The row's reported columns by name: what best_metric and the evaluation listener read.
  EvaluationRow row{num_timesteps,
                    {{"mean_reward", r.mean_return()},
                     {"std_reward", r.std_return()},
                     {"mean_ep_length", r.mean_length()}}};
  if (!std::isnan(success)) row.values["success_rate"] = success;
  for (size_t k = 0; k < metric_keys_.size(); ++k)
    if (!std::isnan(metric_means[k])) row.values[metric_keys_[k]] = metric_means[k];
  if (context_.logger) {
    context_.logger->record("eval/mean_reward", r.mean_return());
    context_.logger->record("eval/mean_ep_length", r.mean_length());
    if (!std::isnan(success)) context_.logger->record("eval/success_rate", success);
    for (size_t k = 0; k < metric_keys_.size(); ++k)
      if (!std::isnan(metric_means[k]))
        context_.logger->record("eval/" + metric_keys_[k], metric_means[k]);
  }

  std::string message = "eval at " + count_of(num_timesteps, "step") + ": return " +
                        format_log_value(r.mean_return()) + " +/- " +
                        format_log_value(r.std_return()) + ", length " +
                        format_log_value(r.mean_length());
  if (!std::isnan(success)) message += ", success rate " + format_log_value(success);
  if (r.mean_return() > best_) best_ = r.mean_return();
  // The value best_model.zip is chosen by (a column no episode reported is NaN: never a best).
  const auto column = row.values.find(config_.best_metric);
  const double chosen = column != row.values.end() ? column->second : std::nan("");
  const double score = config_.best_direction == "minimize" ? -chosen : chosen;
  if (score > best_score_) {
    best_score_ = score;
    context_.save_model("best_model.zip");
    message += config_.best_metric == "mean_reward"
                   ? " (new best, saved best_model.zip)"
                   : " (new best " + config_.best_metric + " " + format_log_value(chosen) +
                         ", saved best_model.zip)";
  }
  context_.message(message);
  if (context_.on_evaluation) {
    stop_reason_ = context_.on_evaluation(row);
    if (!stop_reason_.empty()) return false;
  }
  return check_stop_rules();
}

bool EvalCallback::check_stop_rules() {
  // StopTrainingOnRewardThreshold: continue while best_mean_reward < reward_threshold.
  if (config_.reward_threshold && !(best_ < *config_.reward_threshold)) {
    stop_reason_ = "best mean reward " + format_log_value(best_) +
                   " reached eval.reward_threshold " + format_log_value(*config_.reward_threshold);
    return false;
  }
  // StopTrainingOnNoModelImprovement: its n_calls is the number of evaluations so far.
  if (config_.max_no_improvement_evals) {
    bool stop = false;
    if (evaluations_ > config_.min_evals) {
      if (best_score_ > last_best_) {
        no_improvement_evals_ = 0;
      } else if (++no_improvement_evals_ > *config_.max_no_improvement_evals) {
        stop = true;
      }
    }
    last_best_ = best_score_;
    if (stop) {
      stop_reason_ = "no new best model in the last " +
                     count_of(no_improvement_evals_, "evaluation") +
                     " (eval.max_no_improvement_evals " +
                     std::to_string(*config_.max_no_improvement_evals) + ")";
      return false;
    }
  }
  return true;
}

}  // namespace rlrun

#include "rlrun/tune/zoo_spaces.hpp"

#include <algorithm>
#include <functional>

#include "rlrun/core/errors.hpp"

namespace rlrun::tune {
namespace {

using json = nlohmann::json;

// Suggest-call helpers with the zoo's call shapes (trial.suggest_float / _int / _categorical).
struct Zoo {
  TrialSuggest& trial;
  double float_(const std::string& name, double low, double high, bool log = false) {
    return trial.suggest(name, make_float_distribution(name, low, high, log, std::nullopt))
        .get<double>();
  }
  int64_t int_(const std::string& name, int64_t low, int64_t high) {
    return trial.suggest(name, make_int_distribution(name, low, high, false, 1)).get<int64_t>();
  }
  json categorical(const std::string& name, std::vector<json> choices) {
    return trial.suggest(name, make_categorical_distribution(name, std::move(choices)));
  }
};

void set(std::vector<Override>& out, const std::string& key, const json& value) {
  out.push_back({key, yaml_text_of(value)});
}
void set_yaml(std::vector<Override>& out, const std::string& key, const std::string& yaml) {
  out.push_back({key, yaml});
}

// Activation names map one to one (rlrun's activation_fn takes tanh, relu, ...).
// sample_ppo_params + convert_ppo_params.
std::vector<Override> ppo(Zoo z) {
  std::vector<Override> out;
  const json batch_size = z.categorical("batch_size", {32, 64, 128, 256, 512});
  const json n_steps = z.categorical("n_steps", {32, 64, 128, 256, 512, 1024, 2048});
  const double one_minus_gamma = z.float_("one_minus_gamma", 0.0001, 0.03, true);
  const double one_minus_gae_lambda = z.float_("one_minus_gae_lambda", 0.0001, 0.1, true);
  const double learning_rate = z.float_("learning_rate", 1e-5, 0.002, true);
  const double ent_coef = z.float_("ent_coef", 0.00000001, 0.1, true);
  const json clip_range = z.categorical("clip_range", {0.1, 0.2, 0.3, 0.4});
  const json n_epochs = z.categorical("n_epochs", {1, 5, 10, 20});
  const double max_grad_norm = z.float_("max_grad_norm", 0.3, 2);
  const std::string net_arch = z.categorical("net_arch", {"tiny", "small", "medium"});
  const std::string activation_fn = z.categorical("activation_fn", {"tanh", "relu"});
  z.trial.set_user_attr("gamma", 1 - one_minus_gamma);  // "Display true values"
  set(out, "algo.n_steps", n_steps);
  set(out, "algo.batch_size", batch_size);
  set(out, "algo.gamma", 1 - one_minus_gamma);
  set(out, "algo.gae_lambda", 1 - one_minus_gae_lambda);
  set(out, "algo.learning_rate", learning_rate);
  set(out, "algo.ent_coef", ent_coef);
  set(out, "algo.clip_range", clip_range);
  set(out, "algo.n_epochs", n_epochs);
  set(out, "algo.max_grad_norm", max_grad_norm);
  set_yaml(out, "algo.policy.net_arch",
           net_arch == "tiny"    ? "{pi: [64], vf: [64]}"
           : net_arch == "small" ? "{pi: [64, 64], vf: [64, 64]}"
                                 : "{pi: [256, 256], vf: [256, 256]}");
  set(out, "algo.policy.activation_fn", activation_fn);
  return out;
}

// sample_a2c_params + convert_ppo_params.
std::vector<Override> a2c(Zoo z) {
  std::vector<Override> out;
  const json n_steps = z.categorical("n_steps", {32, 64, 128, 256, 512, 1024, 2048});
  const double one_minus_gamma = z.float_("one_minus_gamma", 0.0001, 0.03, true);
  const double one_minus_gae_lambda = z.float_("one_minus_gae_lambda", 0.0001, 0.1, true);
  const double learning_rate = z.float_("learning_rate", 1e-5, 0.002, true);
  const double max_grad_norm = z.float_("max_grad_norm", 0.3, 2);
  const double ent_coef = z.float_("ent_coef", 0.00000001, 0.1, true);
  const std::string net_arch = z.categorical("net_arch", {"small", "medium"});
  const std::string activation_fn = z.categorical("activation_fn", {"tanh", "relu"});
  z.trial.set_user_attr("gamma", 1 - one_minus_gamma);
  set(out, "algo.n_steps", n_steps);
  set(out, "algo.gamma", 1 - one_minus_gamma);
  set(out, "algo.gae_lambda", 1 - one_minus_gae_lambda);
  set(out, "algo.learning_rate", learning_rate);
  set(out, "algo.ent_coef", ent_coef);
  set(out, "algo.max_grad_norm", max_grad_norm);
  set_yaml(
      out, "algo.policy.net_arch",
      net_arch == "small" ? "{pi: [64, 64], vf: [64, 64]}" : "{pi: [256, 256], vf: [256, 256]}");
  set(out, "algo.policy.activation_fn", activation_fn);
  return out;
}

// sample_trpo_params + convert_onpolicy_params (rl-zoo 2.6 and later): powers of two for the
// batch and rollout sizes; the user attributes show the true values.
std::vector<Override> trpo(Zoo z) {
  std::vector<Override> out;
  const int64_t batch_size_pow = z.int_("batch_size_pow", 2, 10);
  const int64_t n_steps_pow = z.int_("n_steps_pow", 5, 12);
  const double one_minus_gamma = z.float_("one_minus_gamma", 0.0001, 0.03, true);
  const double one_minus_gae_lambda = z.float_("one_minus_gae_lambda", 0.0001, 0.1, true);
  const double learning_rate = z.float_("learning_rate", 1e-5, 0.002, true);
  const int64_t n_critic_updates = z.int_("n_critic_updates", 5, 30);
  const int64_t cg_max_steps = z.int_("cg_max_steps", 5, 30);
  const double target_kl = z.float_("target_kl", 0.001, 0.1, true);
  const std::string net_arch = z.categorical("net_arch", {"small", "medium"});
  const std::string activation_fn = z.categorical("activation_fn", {"tanh", "relu"});
  z.trial.set_user_attr("gamma", 1 - one_minus_gamma);
  z.trial.set_user_attr("n_steps", int64_t{1} << n_steps_pow);
  z.trial.set_user_attr("batch_size", int64_t{1} << batch_size_pow);
  set(out, "algo.n_steps", int64_t{1} << n_steps_pow);
  set(out, "algo.batch_size", int64_t{1} << batch_size_pow);
  set(out, "algo.gamma", 1 - one_minus_gamma);
  set(out, "algo.gae_lambda", 1 - one_minus_gae_lambda);
  set(out, "algo.learning_rate", learning_rate);
  set(out, "algo.n_critic_updates", n_critic_updates);
  set(out, "algo.cg_max_steps", cg_max_steps);
  set(out, "algo.target_kl", target_kl);
  set_yaml(
      out, "algo.policy.net_arch",
      net_arch == "small" ? "{pi: [64, 64], vf: [64, 64]}" : "{pi: [256, 256], vf: [256, 256]}");
  set(out, "algo.policy.activation_fn", activation_fn);
  return out;
}

// sample_ars_params + convert_ars_params: n_delta a power of two, n_top a fraction of it (at
// least one).
std::vector<Override> ars(Zoo z) {
  std::vector<Override> out;
  const int64_t n_delta = int64_t{1} << z.int_("n_delta_pow", 2, 6);
  const double learning_rate = z.float_("learning_rate", 1e-5, 0.002, true);
  const double delta_std = z.float_("delta_std", 0.01, 0.3);
  const double top_frac_size = z.float_("top_frac_size", 0.05, 1.0);
  set(out, "algo.n_delta", n_delta);
  set(out, "algo.learning_rate", learning_rate);
  set(out, "algo.delta_std", delta_std);
  set(out, "algo.n_top",
      std::max<int64_t>(static_cast<int64_t>(top_frac_size * static_cast<double>(n_delta)), 1));
  return out;
}

// sample_her_params: appended by the off-policy spaces when the experiment uses HER.
void her(Zoo z, std::vector<Override>& out) {
  set(out, "algo.replay_buffer_kwargs.n_sampled_goal", z.int_("n_sampled_goal", 1, 5));
  set(out, "algo.replay_buffer_kwargs.goal_selection_strategy",
      z.categorical("goal_selection_strategy", {"final", "episode", "future"}));
}

const std::vector<json> kGammas{0.9, 0.95, 0.98, 0.99, 0.995, 0.999, 0.9999};
const std::vector<json> kTaus{0.001, 0.005, 0.01, 0.02, 0.05, 0.08};
const std::vector<json> kTrainFreqs{1, 4, 8, 16, 32, 64, 128, 256, 512};

std::string big_net_arch(const std::string& name) {
  return name == "small" ? "[64, 64]" : name == "medium" ? "[256, 256]" : "[400, 300]";
}

// sample_dqn_params.
std::vector<Override> dqn(Zoo z, bool uses_her) {
  std::vector<Override> out;
  const json gamma = z.categorical("gamma", kGammas);
  const double learning_rate = z.float_("learning_rate", 1e-5, 1, true);
  const json batch_size = z.categorical("batch_size", {16, 32, 64, 100, 128, 256, 512});
  const json buffer_size = z.categorical("buffer_size", {10000, 50000, 100000, 1000000});
  const double exploration_final_eps = z.float_("exploration_final_eps", 0, 0.2);
  const double exploration_fraction = z.float_("exploration_fraction", 0, 0.5);
  const json target_update_interval =
      z.categorical("target_update_interval", {1, 1000, 5000, 10000, 15000, 20000});
  const json learning_starts = z.categorical("learning_starts", {0, 1000, 5000, 10000, 20000});
  const json train_freq = z.categorical("train_freq", {1, 4, 8, 16, 128, 256, 1000});
  const json subsample_steps = z.categorical("subsample_steps", {1, 2, 4, 8});
  const int64_t gradient_steps =
      std::max<int64_t>(train_freq.get<int64_t>() / subsample_steps.get<int64_t>(), 1);
  const std::string net_arch = z.categorical("net_arch", {"tiny", "small", "medium"});
  set(out, "algo.gamma", gamma);
  set(out, "algo.learning_rate", learning_rate);
  set(out, "algo.batch_size", batch_size);
  set(out, "algo.buffer_size", buffer_size);
  set(out, "algo.train_freq", train_freq);
  set(out, "algo.gradient_steps", gradient_steps);
  set(out, "algo.exploration_fraction", exploration_fraction);
  set(out, "algo.exploration_final_eps", exploration_final_eps);
  set(out, "algo.target_update_interval", target_update_interval);
  set(out, "algo.learning_starts", learning_starts);
  set_yaml(out, "algo.policy.net_arch",
           net_arch == "tiny"    ? "[64]"
           : net_arch == "small" ? "[64, 64]"
                                 : "[256, 256]");
  if (uses_her) her(z, out);
  return out;
}

// sample_qrdqn_params: sample_dqn_params with sample_qrdqn set, which adds n_quantiles last.
std::vector<Override> qrdqn(Zoo z, bool uses_her) {
  std::vector<Override> out = dqn(z, false);
  set(out, "algo.policy.n_quantiles", z.int_("n_quantiles", 5, 200));
  if (uses_her) her(z, out);
  return out;
}

// sample_sac_params (also the first half of sample_tqc_params).
std::vector<Override> sac(Zoo z, bool uses_her) {
  std::vector<Override> out;
  const json gamma = z.categorical("gamma", kGammas);
  const double learning_rate = z.float_("learning_rate", 1e-5, 1, true);
  const json batch_size = z.categorical("batch_size", {16, 32, 64, 128, 256, 512, 1024, 2048});
  const json buffer_size = z.categorical("buffer_size", {10000, 100000, 1000000});
  const json learning_starts = z.categorical("learning_starts", {0, 1000, 10000, 20000});
  const json train_freq = z.categorical("train_freq", kTrainFreqs);
  const json tau = z.categorical("tau", kTaus);
  const double log_std_init = z.float_("log_std_init", -4, 1);
  const std::string net_arch = z.categorical("net_arch", {"small", "medium", "big"});
  set(out, "algo.gamma", gamma);
  set(out, "algo.learning_rate", learning_rate);
  set(out, "algo.batch_size", batch_size);
  set(out, "algo.buffer_size", buffer_size);
  set(out, "algo.learning_starts", learning_starts);
  set(out, "algo.train_freq", train_freq);
  set(out, "algo.gradient_steps", train_freq);
  set(out, "algo.ent_coef", "auto");
  set(out, "algo.tau", tau);
  set(out, "algo.target_entropy", "auto");
  set(out, "algo.policy.log_std_init", log_std_init);
  set_yaml(out, "algo.policy.net_arch", big_net_arch(net_arch));
  if (uses_her) her(z, out);
  return out;
}

// sample_td3_params and sample_ddpg_params (the same space).
std::vector<Override> td3(Zoo z, bool uses_her) {
  std::vector<Override> out;
  const json gamma = z.categorical("gamma", kGammas);
  const double learning_rate = z.float_("learning_rate", 1e-5, 1, true);
  const json batch_size = z.categorical("batch_size", {16, 32, 64, 100, 128, 256, 512, 1024, 2048});
  const json buffer_size = z.categorical("buffer_size", {10000, 100000, 1000000});
  const json tau = z.categorical("tau", kTaus);
  const json train_freq = z.categorical("train_freq", kTrainFreqs);
  const json noise_type = z.categorical("noise_type", {"ornstein-uhlenbeck", "normal", nullptr});
  const double noise_std = z.float_("noise_std", 0, 1);
  const std::string net_arch = z.categorical("net_arch", {"small", "medium", "big"});
  set(out, "algo.gamma", gamma);
  set(out, "algo.learning_rate", learning_rate);
  set(out, "algo.batch_size", batch_size);
  set(out, "algo.buffer_size", buffer_size);
  set(out, "algo.train_freq", train_freq);
  set(out, "algo.gradient_steps", train_freq);
  set_yaml(out, "algo.policy.net_arch", big_net_arch(net_arch));
  set(out, "algo.tau", tau);
  // None: no action noise (SB3's default for TD3/DDPG).
  set(out, "algo.noise_type", noise_type.is_null() ? json("") : noise_type);
  if (!noise_type.is_null()) set(out, "algo.noise_std", noise_std);
  if (uses_her) her(z, out);
  return out;
}

// sample_tqc_params: SAC's space, then the quantiles (the upper bound of the second depends on
// the first, as in the zoo).
std::vector<Override> tqc(Zoo z, bool uses_her) {
  std::vector<Override> out = sac(z, uses_her);
  const int64_t n_quantiles = z.int_("n_quantiles", 5, 50);
  const int64_t drop = z.int_("top_quantiles_to_drop_per_net", 0, n_quantiles - 1);
  set(out, "algo.policy.n_quantiles", n_quantiles);
  set(out, "algo.top_quantiles_to_drop_per_net", drop);
  return out;
}

using SpaceFunction = std::function<std::vector<Override>(Zoo)>;

// Answers suggest() from a finished trial's parameters (for --best-config / --trial).
class FixedSuggest : public TrialSuggest {
 public:
  explicit FixedSuggest(const json& params) : params_(params) {}
  json suggest(const std::string& name, const Distribution&) override {
    if (!params_.contains(name)) throw RuntimeFailure("the trial has no parameter '" + name + "'");
    return params_[name];
  }
  void set_user_attr(const std::string&, const json&) override {}

 private:
  const json& params_;
};

class ZooSpace : public StudySpace {
 public:
  ZooSpace(std::string name, SpaceFunction function)
      : name_(std::move(name)), function_(std::move(function)) {}
  std::vector<Override> sample(TrialSuggest& trial) const override { return function_(Zoo{trial}); }
  std::vector<Override> overrides_for(const json& params) const override {
    FixedSuggest fixed(params);
    return function_(Zoo{fixed});
  }
  std::string describe() const override {
    return "rl-zoo's " + name_ + " (rl_zoo3/hyperparams_opt.py)";
  }

 private:
  std::string name_;
  SpaceFunction function_;
};

}  // namespace

std::unique_ptr<StudySpace> zoo_space(const std::string& algo_id, bool uses_her) {
  if (algo_id == "PPO") return std::make_unique<ZooSpace>("sample_ppo_params", ppo);
  // rl-zoo's sample_ppo_lstm_params returns sample_ppo_params (its LSTM sizes commented out).
  if (algo_id == "RecurrentPPO") return std::make_unique<ZooSpace>("sample_ppo_lstm_params", ppo);
  if (algo_id == "A2C") return std::make_unique<ZooSpace>("sample_a2c_params", a2c);
  if (algo_id == "TRPO") return std::make_unique<ZooSpace>("sample_trpo_params", trpo);
  if (algo_id == "ARS") return std::make_unique<ZooSpace>("sample_ars_params", ars);
  const std::string suffix = uses_her ? " + sample_her_params" : "";
  if (algo_id == "DQN")
    return std::make_unique<ZooSpace>("sample_dqn_params" + suffix,
                                      [uses_her](Zoo z) { return dqn(z, uses_her); });
  if (algo_id == "QRDQN")
    return std::make_unique<ZooSpace>("sample_qrdqn_params" + suffix,
                                      [uses_her](Zoo z) { return qrdqn(z, uses_her); });
  if (algo_id == "SAC")
    return std::make_unique<ZooSpace>("sample_sac_params" + suffix,
                                      [uses_her](Zoo z) { return sac(z, uses_her); });
  if (algo_id == "TD3" || algo_id == "DDPG")
    return std::make_unique<ZooSpace>(
        (algo_id == "TD3" ? "sample_td3_params" : "sample_ddpg_params") + suffix,
        [uses_her](Zoo z) { return td3(z, uses_her); });
  if (algo_id == "TQC")
    return std::make_unique<ZooSpace>("sample_tqc_params" + suffix,
                                      [uses_her](Zoo z) { return tqc(z, uses_her); });
  throw UsageError(
      "rl-zoo has no search space for " + algo_id +
      " (PPO, RecurrentPPO, A2C, TRPO, ARS, DQN, QRDQN, SAC, TD3, DDPG, TQC have one); write the "
      "parameters out");
}

}  // namespace rlrun::tune

#include "rlrun/runtime/io/sb3/sb3_model_writer.hpp"

#include <yaml-cpp/yaml.h>

#include <cstring>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <utility>

#include "rlrun/core/base64.hpp"
#include "rlrun/core/errors.hpp"
#include "rlrun/core/float_format.hpp"
#include "rlrun/core/pickle_writer.hpp"
#include "rlrun/core/quoted_text.hpp"
#include "rlrun/core/schedule.hpp"
#include "rlrun/core/torch_file_writer.hpp"
#include "rlrun/runtime/io/sb3/sb3_net_arch.hpp"
#include "rlrun/runtime/io/sb3/sb3_spaces.hpp"

namespace rlrun {

// A named namespace: a unity build joins this file with the reader's (sb3_model_file.cpp).
namespace sb3_writer {

// SB3 writes `data` in its attributes' order; an ordered JSON keeps ours readable the same way.
using Json = nlohmann::ordered_json;

// Pickles SB3's `data` entries are read with (cloudpickle.loads): protocol 4, as every
// Python 3 reads.
constexpr int kDataProtocol = 4;

enum class Family { kActorCritic, kDqn, kSac, kTd3 };

struct ClassRef {
  std::string module;
  std::string name;
  std::string str() const { return "<class '" + module + "." + name + "'>"; }
};

// What SB3's class for each algorithm is, and its default learning rate (the optimizer's lr
// when the configuration has none).
struct Sb3Algorithm {
  Family family;
  const char* policy_module;
  const char* mlp_policy;
  const char* multi_input_policy;
  double default_learning_rate;
  const char* load_class;  // what opens the file in Python
  const char* cnn_policy;  // its CnnPolicy class (in policy_module)
  // sb3-contrib's distributional variants: QR-DQN (DQN's family, its network quantile_net)
  // and TQC (SAC's family): n_quantiles outputs per action or per critic.
  bool quantiles = false;
};

const Sb3Algorithm* sb3_algorithm(const std::string& id) {
  static const std::map<std::string, Sb3Algorithm> known = {
      {"PPO",
       {Family::kActorCritic, "stable_baselines3.common.policies", "ActorCriticPolicy",
        "MultiInputActorCriticPolicy", 3e-4, "stable_baselines3.PPO", "ActorCriticCnnPolicy"}},
      {"A2C",
       {Family::kActorCritic, "stable_baselines3.common.policies", "ActorCriticPolicy",
        "MultiInputActorCriticPolicy", 7e-4, "stable_baselines3.A2C", "ActorCriticCnnPolicy"}},
      {"DQN",
       {Family::kDqn, "stable_baselines3.dqn.policies", "DQNPolicy", "MultiInputPolicy", 1e-4,
        "stable_baselines3.DQN", "CnnPolicy"}},
      {"SAC",
       {Family::kSac, "stable_baselines3.sac.policies", "SACPolicy", "MultiInputPolicy", 3e-4,
        "stable_baselines3.SAC", "CnnPolicy"}},
      {"TD3",
       {Family::kTd3, "stable_baselines3.td3.policies", "TD3Policy", "MultiInputPolicy", 1e-3,
        "stable_baselines3.TD3", "CnnPolicy"}},
      {"DDPG",
       {Family::kTd3, "stable_baselines3.td3.policies", "TD3Policy", "MultiInputPolicy", 1e-3,
        "stable_baselines3.DDPG", "CnnPolicy"}},
      // sb3-contrib 2.4: PPO's actor-critic under their own policy classes.
      {"MaskablePPO",
       {Family::kActorCritic, "sb3_contrib.common.maskable.policies", "MaskableActorCriticPolicy",
        "MaskableMultiInputActorCriticPolicy", 3e-4, "sb3_contrib.MaskablePPO",
        "MaskableActorCriticCnnPolicy"}},
      {"RecurrentPPO",
       {Family::kActorCritic, "sb3_contrib.common.recurrent.policies", "RecurrentActorCriticPolicy",
        "RecurrentMultiInputActorCriticPolicy", 3e-4, "sb3_contrib.RecurrentPPO",
        "RecurrentActorCriticCnnPolicy"}},
      {"TRPO",
       {Family::kActorCritic, "stable_baselines3.common.policies", "ActorCriticPolicy",
        "MultiInputActorCriticPolicy", 1e-3, "sb3_contrib.TRPO", "ActorCriticCnnPolicy"}},
      {"QRDQN",
       {Family::kDqn, "sb3_contrib.qrdqn.policies", "QRDQNPolicy", "MultiInputPolicy", 5e-5,
        "sb3_contrib.QRDQN", "CnnPolicy", true}},
      {"TQC",
       {Family::kSac, "sb3_contrib.tqc.policies", "TQCPolicy", "MultiInputPolicy", 3e-4,
        "sb3_contrib.TQC", "CnnPolicy", true}},
  };
  const auto found = known.find(id);
  return found == known.end() ? nullptr : &found->second;
}

// The hyperparameters each SB3 class takes (its __init__'s arguments that `data` holds), under
// the names rlrun's configuration shares with SB3. train_freq and the schedules are converted.
const std::vector<std::string>& hyperparameters(const std::string& id) {
  static const std::vector<std::string> off_policy = {
      "learning_rate", "buffer_size", "learning_starts", "batch_size",
      "tau",           "gamma",       "gradient_steps",  "optimize_memory_usage",
      "train_freq",    "use_sde",     "sde_sample_freq", "use_sde_at_warmup"};
  const auto with = [](std::vector<std::string> base, std::vector<std::string> more) {
    base.insert(base.end(), more.begin(), more.end());
    return base;
  };
  static const std::vector<std::string> ppo = {
      "learning_rate", "n_steps",         "batch_size",
      "n_epochs",      "gamma",           "gae_lambda",
      "clip_range",    "clip_range_vf",   "normalize_advantage",
      "ent_coef",      "vf_coef",         "max_grad_norm",
      "use_sde",       "sde_sample_freq", "target_kl"};
  static const std::map<std::string, std::vector<std::string>> known = {
      {"PPO", ppo},
      {"RecurrentPPO", ppo},
      {"TRPO",
       {"learning_rate", "n_steps", "batch_size", "gamma", "cg_max_steps", "cg_damping",
        "line_search_shrinking_factor", "line_search_max_iter", "n_critic_updates", "gae_lambda",
        "use_sde", "sde_sample_freq", "normalize_advantage", "target_kl", "sub_sampling_factor"}},
      {"MaskablePPO",
       {"learning_rate", "n_steps", "batch_size", "n_epochs", "gamma", "gae_lambda", "clip_range",
        "clip_range_vf", "normalize_advantage", "ent_coef", "vf_coef", "max_grad_norm",
        "target_kl"}},
      {"A2C",
       {"learning_rate", "n_steps", "gamma", "gae_lambda", "ent_coef", "vf_coef", "max_grad_norm",
        "rms_prop_eps", "use_rms_prop", "use_sde", "sde_sample_freq", "normalize_advantage"}},
      {"DQN",
       with(off_policy, {"target_update_interval", "exploration_fraction",
                         "exploration_initial_eps", "exploration_final_eps", "max_grad_norm"})},
      {"SAC", with(off_policy, {"ent_coef", "target_update_interval", "target_entropy"})},
      {"TQC", with(off_policy, {"ent_coef", "target_update_interval", "target_entropy",
                                "top_quantiles_to_drop_per_net"})},
      {"TD3", with(off_policy, {"policy_delay", "target_policy_noise", "target_noise_clip"})},
      {"DDPG", off_policy},
      {"QRDQN",
       with(off_policy, {"target_update_interval", "exploration_fraction",
                         "exploration_initial_eps", "exploration_final_eps", "max_grad_norm"})},
  };
  return known.at(id);
}

// A scalar of the resolved configuration as JSON: null, bool, int, float or string.
Json scalar_json(const YAML::Node& node) {
  if (!node || node.IsNull()) return nullptr;
  if (node.Tag() == "!") return node.Scalar();  // quoted: a string
  bool b = false;
  int64_t i = 0;
  double d = 0.0;
  if (YAML::convert<bool>::decode(node, b)) return b;
  if (YAML::convert<int64_t>::decode(node, i)) return i;
  if (YAML::convert<double>::decode(node, d)) return d;
  return node.Scalar();
}

// JSON data as a Python value: None, bool, int, float, str, list, dict.
void pickle_json(PickleWriter& p, const Json& value) {
  if (value.is_null()) return p.none();
  if (value.is_boolean()) return p.boolean(value.get<bool>());
  if (value.is_number_integer()) return p.integer(value.get<int64_t>());
  if (value.is_number()) return p.real(value.get<double>());
  if (value.is_string()) return p.text(value.get<std::string>());
  if (value.is_array()) {
    p.empty_list();
    if (value.empty()) return;
    p.mark();
    for (const Json& item : value) pickle_json(p, item);
    return p.appends();
  }
  p.empty_dict();
  if (value.empty()) return;
  p.mark();
  for (const auto& [key, item] : value.items()) {
    p.text(key);
    pickle_json(p, item);
  }
  p.set_items();
}

// {":type:": ..., ":serialized:": base64 of the pickle, plus JSON-able attributes}: the form of
// SB3's data_to_json for what JSON cannot hold; only ":serialized:" is read back.
Json serialized(const std::string& type, std::vector<uint8_t> pickle,
                const Json& attributes = Json::object()) {
  Json out;
  out[":type:"] = type;
  out[":serialized:"] = encode_base64(pickle);
  for (const auto& [key, value] : attributes.items()) out[key] = value;
  return out;
}

// policy_kwargs: plain values, and the torch classes some of them name.
struct PolicyKwargs {
  Json plain = Json::object();
  std::vector<std::pair<std::string, ClassRef>> classes;

  Json entry() const {
    PickleWriter p(kDataProtocol);
    p.empty_dict();
    p.mark();
    for (const auto& [key, value] : plain.items()) {
      p.text(key);
      pickle_json(p, value);
    }
    for (const auto& [key, ref] : classes) {
      p.text(key);
      p.global_ref(ref.module, ref.name);
    }
    p.set_items();
    Json attributes = plain;  // what SB3 writes beside: JSON, or str() of a class
    for (const auto& [key, ref] : classes) attributes[key] = ref.str();
    return serialized("<class 'dict'>", p.finish(), attributes);
  }
};

// One optimizer's state_dict: its param group as SB3 built the optimizer, over `n_params`
// parameters, and no per-parameter state (torch's load_state_dict accepts an empty state).
std::vector<uint8_t> optimizer_file(const Json& group, int64_t n_params) {
  TorchFileWriter writer;
  PickleWriter& p = writer.pickle();
  p.empty_dict();
  p.mark();
  p.text("state");
  p.empty_dict();
  p.text("param_groups");
  p.empty_list();
  p.mark();
  p.empty_dict();
  p.mark();
  for (const auto& [key, value] : group.items()) {
    p.text(key);
    if (key == "betas") {  // a tuple in torch's Adam
      p.mark();
      for (const Json& beta : value) p.real(beta.get<double>());
      p.tuple_from_mark();
    } else {
      pickle_json(p, value);
    }
  }
  p.text("params");
  std::vector<int64_t> ids(static_cast<std::size_t>(n_params));
  for (int64_t i = 0; i < n_params; ++i) ids[static_cast<std::size_t>(i)] = i;
  p.int_list(ids);
  p.set_items();
  p.appends();
  p.set_items();
  return writer.finish();
}

// torch.optim.Adam's param group (torch 1.13's keys; torch 2.x reads them and fills its own).
Json adam_group(double lr, double eps) {
  return Json{{"lr", lr},           {"betas", {0.9, 0.999}}, {"eps", eps},
              {"weight_decay", 0},  {"amsgrad", false},      {"maximize", false},
              {"foreach", nullptr}, {"capturable", false},   {"differentiable", false},
              {"fused", false}};
}

// torch.optim.RMSprop's, as A2C builds it (alpha 0.99, eps rms_prop_eps, weight_decay 0).
Json rmsprop_group(double lr, double eps) {
  return Json{{"lr", lr},           {"momentum", 0},     {"alpha", 0.99},
              {"eps", eps},         {"centered", false}, {"weight_decay", 0},
              {"foreach", nullptr}, {"maximize", false}, {"differentiable", false}};
}

ClassRef activation_class(const std::string& configured) {
  static const std::map<std::string, std::string> names = {{"tanh", "Tanh"},
                                                           {"relu", "ReLU"},
                                                           {"elu", "ELU"},
                                                           {"leaky_relu", "LeakyReLU"},
                                                           {"gelu", "GELU"}};
  std::string key = configured;
  for (const auto& [rlrun_name, torch_name] : names)
    if (configured == "nn." + torch_name || configured == torch_name) key = rlrun_name;
  const auto found = names.find(key);
  if (found == names.end())
    throw RuntimeFailure("activation '" + quoted_text(configured) + "' has no torch.nn class");
  return {"torch.nn.modules.activation", found->second};
}

class Sb3Writer {
 public:
  Sb3Writer(const LoadedModel& model, const Sb3Algorithm& algo)
      : model_(model),
        algo_(algo),
        id_(model.file.meta.algorithm),
        config_(model.experiment.resolved["algo"]) {
    model_.algorithm->save(tensors_);
    if (tensors_.empty()) fail("the model holds no tensors");
    for (const auto& [name, tensor] : tensors_)
      if (name.ends_with("features_extractor.cnn.0.weight")) cnn_ = true;
    combined_cnn_ = sb3_has_combined_cnn(tensors_);
  }

  Sb3ModelExport write() {
    check_policy();
    Sb3ModelExport out;
    Json data = header_entries();
    for (const std::string& name : hyperparameters(id_)) add_hyperparameter(data, name);
    if (id_ == "DDPG") {  // SB3's DDPG is TD3 with these (stable_baselines3/ddpg/ddpg.py)
      data["policy_delay"] = 1;
      data["target_noise_clip"] = 0.0;
      data["target_policy_noise"] = 0.1;
    }
    const std::string text = data.dump(4);
    out.members["data"] = std::vector<uint8_t>(text.begin(), text.end());
    write_tensors(out.members);
    const std::string version = kSb3FormatVersion;
    out.members["_stable_baselines3_version"] =
        std::vector<uint8_t>(version.begin(), version.end());
    const std::string info = std::string("- Written by: rlrun ") + RLRUN_VERSION +
                             " (rlrun export --format sb3)\n- Stable-Baselines3: " + version +
                             " (the format written)\n";
    out.members["system_info.txt"] = std::vector<uint8_t>(info.begin(), info.end());
    out.notes = std::move(notes_);
    out.load_class = algo_.load_class;
    return out;
  }

 private:
  [[noreturn]] void fail(const std::string& why) const {
    throw RuntimeFailure("cannot write " + model_.file.path + " as an SB3 model file: " + why);
  }

  // SB3's CnnPolicy (NatureCNN over an image; shared or separate extractors as configured).
  bool writes_cnn() const {
    return cnn_ && observation_space().is_box() && observation_space().shape().size() == 3;
  }
  // SB3's MultiInputPolicy whose CombinedExtractor has a NatureCNN per image key.
  bool writes_combined_cnn() const { return combined_cnn_ && observation_space().is_dict(); }

  void check_policy() const {
    for (const auto& [name, tensor] : tensors_) {
      if (name.find("features_extractor") != std::string::npos && !writes_cnn() &&
          !writes_combined_cnn())
        fail("its policy has a features extractor with weights ('" + quoted_text(name) +
             "') that SB3's MlpPolicy, MultiInputPolicy and CnnPolicy do not have");
      if (!is_policy_tensor(name) && !kAlgorithmAttributes.count(name))
        fail("its tensor '" + quoted_text(name) + "' has no place in SB3's file");
      if (is_policy_tensor(name) && tensor.dtype != DType::kFloat32)
        fail("tensor '" + quoted_text(name) + "' is not float32");
    }
  }

  // Tensors of rlrun's model that are attributes of SB3's algorithm, not of its policy.
  inline static const std::set<std::string> kAlgorithmAttributes = {
      "log_ent_coef",       // SAC: pytorch_variables.pth
      "ent_coef_tensor",    // SAC with a fixed coefficient: pytorch_variables.pth
      "exploration_rate"};  // DQN: `data`, a float

  const Space& observation_space() const { return model_.env->observation_space(); }

  Json header_entries() {
    Json data;
    const bool dict = observation_space().is_dict();
    const char* policy_module = algo_.policy_module;
    const char* policy_class = writes_cnn() ? algo_.cnn_policy
                               : dict       ? algo_.multi_input_policy
                                            : algo_.mlp_policy;
    data["policy_class"] =
        serialized("<class 'abc.ABCMeta'>", global_pickle(policy_module, policy_class),
                   {{"__module__", policy_module}});
    data["verbose"] = 0;
    data["policy_kwargs"] = policy_kwargs().entry();
    data["num_timesteps"] = model_.file.meta.num_timesteps;
    data["_total_timesteps"] = model_.file.meta.num_timesteps;
    data["_num_timesteps_at_start"] = 0;
    const Json seed = scalar_json(model_.experiment.resolved["run"]["seed"]);
    data["seed"] = seed.is_number_integer() ? seed : Json(nullptr);
    data["action_noise"] = nullptr;
    if (config_["action_noise"] && !config_["action_noise"].IsNull())
      notes_.push_back(
          "the action noise of training is not written: give SB3's load(..., action_noise=...) "
          "to train on with it");
    data["tensorboard_log"] = nullptr;
    data["_last_obs"] = nullptr;
    data["_episode_num"] = 0;
    // SB3 keeps the space its VecTransposeImage made (channels first) for a CnnPolicy.
    // (and each image key of a Dict).
    data["observation_space"] =
        space_entry(writes_cnn() ? channels_first_image(observation_space())
                                 : channels_first_dict_images(observation_space()));
    data["action_space"] = space_entry(model_.env->action_space());
    const Json n_envs = scalar_json(model_.experiment.resolved["env"]["n_envs"]);
    data["n_envs"] = n_envs.is_number_integer() ? n_envs : Json(1);
    if (const auto rate = tensors_.find("exploration_rate");
        rate != tensors_.end() && rate->second.numel() == 1) {
      if (rate->second.dtype == DType::kFloat64)
        data["exploration_rate"] = rate->second.data<double>()[0];
      else if (rate->second.dtype == DType::kFloat32)
        data["exploration_rate"] = static_cast<double>(rate->second.data<float>()[0]);
    }
    note_wrappers();
    return data;
  }

  static std::vector<uint8_t> global_pickle(const std::string& module, const std::string& name) {
    PickleWriter p(kDataProtocol);
    p.global_ref(module, name);
    return p.finish();
  }

  static Json space_entry(const Space& space) {
    PickleWriter p(kDataProtocol);
    pickle_gymnasium_space(p, space);
    return serialized("<class '" + gymnasium_space_class(space) + "'>", p.finish());
  }

  // The env's wrappers are rlrun's: SB3's file has no place for them, and the policy expects
  // the observations they make.
  void note_wrappers() {
    const YAML::Node env = model_.experiment.resolved["env"];
    std::string names;
    if (env["wrappers"] && env["wrappers"].IsSequence())
      for (const YAML::Node& wrapper : env["wrappers"]) {
        const YAML::Node id = wrapper.IsMap() ? wrapper["id"] : wrapper;
        if (id && id.IsScalar()) names += (names.empty() ? "" : ", ") + quoted_text(id.Scalar());
      }
    if (env["normalize"] && !env["normalize"].IsNull() &&
        !(env["normalize"].IsScalar() && env["normalize"].Scalar() == "false"))
      names += std::string(names.empty() ? "" : ", ") + "normalize (VecNormalize)";
    if (!names.empty())
      notes_.push_back("the env's wrappers (" + names +
                       ") are not in SB3's file: the policy expects the observations they make, "
                       "so wrap the env the same way in SB3");
  }

  std::string activation_name() const {
    const YAML::Node configured = config_["policy"]["activation_fn"];
    if (configured && configured.IsScalar()) return configured.Scalar();
    return algo_.family == Family::kActorCritic ? "tanh" : "relu";
  }

  // Copies the policy settings SB3's policy class of this family takes, if configured.
  void copy_policy_settings(PolicyKwargs& kwargs, const std::vector<std::string>& names) const {
    for (const std::string& name : names) {
      const YAML::Node value = config_["policy"][name];
      if (value && value.IsScalar()) kwargs.plain[name] = scalar_json(value);
    }
  }

  PolicyKwargs policy_kwargs() const {
    PolicyKwargs kwargs;
    switch (algo_.family) {
      case Family::kActorCritic:
        kwargs.plain["net_arch"] = {{"pi", sb3_layer_widths(tensors_, "mlp_extractor.policy_net.")},
                                    {"vf", sb3_layer_widths(tensors_, "mlp_extractor.value_net.")}};
        copy_policy_settings(kwargs,
                             {"ortho_init", "share_features_extractor", "normalize_images"});
        // MaskableActorCriticPolicy has no continuous-action settings (Discrete actions only).
        if (id_ != "MaskablePPO")
          copy_policy_settings(kwargs, {"log_std_init", "full_std", "use_expln"});
        if (id_ == "RecurrentPPO")
          copy_policy_settings(
              kwargs, {"lstm_hidden_size", "n_lstm_layers", "shared_lstm", "enable_critic_lstm"});
        break;
      case Family::kDqn:
        kwargs.plain["net_arch"] = sb3_hidden_widths(tensors_, q_net() + ".");
        copy_policy_settings(kwargs, {"normalize_images"});
        if (algo_.quantiles) add_qrdqn_kwargs(kwargs);
        break;
      case Family::kSac:
      case Family::kTd3:
        kwargs.plain["net_arch"] = {
            {"pi", algo_.family == Family::kSac ? sb3_layer_widths(tensors_, "actor.latent_pi.")
                                                : sb3_hidden_widths(tensors_, "actor.mu.")},
            {"qf", sb3_hidden_widths(tensors_, "critic.qf0.")}};
        kwargs.plain["n_critics"] = sb3_critic_count(tensors_);
        if (algo_.quantiles) {  // TQC: each critic's output is its quantiles
          const std::vector<int> widths = sb3_layer_widths(tensors_, "critic.qf0.");
          if (widths.empty()) fail("its critic has no output layer");
          kwargs.plain["n_quantiles"] = widths.back();
        }
        if (algo_.family == Family::kSac) {
          // SAC's __init__ puts use_sde into policy_kwargs (off_policy_algorithm.py).
          kwargs.plain["use_sde"] = uses_sde();
          copy_policy_settings(kwargs, {"log_std_init", "use_expln", "clip_mean",
                                        "share_features_extractor", "normalize_images"});
        } else {
          copy_policy_settings(kwargs, {"share_features_extractor", "normalize_images"});
        }
        break;
    }
    // NatureCNN is CnnPolicy's default class, CombinedExtractor MultiInputPolicy's: their
    // widths are what varies.
    if (writes_cnn())
      kwargs.plain["features_extractor_kwargs"] = {{"features_dim", features_dim()}};
    if (writes_combined_cnn())
      kwargs.plain["features_extractor_kwargs"] = {{"cnn_output_dim", features_dim()}};
    kwargs.classes.emplace_back("activation_fn", activation_class(activation_name()));
    if (uses_rms_prop()) {  // A2C's __init__ does this (stable_baselines3/a2c/a2c.py)
      kwargs.classes.emplace_back("optimizer_class", ClassRef{"torch.optim.rmsprop", "RMSprop"});
      kwargs.plain["optimizer_kwargs"] = {
          {"alpha", 0.99}, {"eps", rms_prop_eps()}, {"weight_decay", 0}};
    }
    return kwargs;
  }

  // NatureCNN's output width (a CombinedExtractor's per image key), off the first extractor's
  // linear layer.
  int64_t features_dim() const {
    for (const auto& [name, tensor] : tensors_)
      if (name.find("features_extractor.") != std::string::npos &&
          name.ends_with("linear.0.weight") && tensor.shape.size() == 2)
        return tensor.shape[0];
    fail("its NatureCNN has no linear layer");
  }

  // SAC's and TQC's critic optimizer leaves out a features extractor shared with the actor
  // (sac/policies.py, tqc/policies.py _build); TD3's takes all the critic's parameters.
  bool critic_optimizer_skips_extractor() const {
    return algo_.family == Family::kSac && (writes_cnn() || writes_combined_cnn()) &&
           flag_in_policy("share_features_extractor", false);
  }
  bool flag_in_policy(const char* name, bool fallback) const {
    const Json value = scalar_json(config_["policy"][name]);
    return value.is_boolean() ? value.get<bool>() : fallback;
  }

  // "q_net", or QR-DQN's "quantile_net": the network DQN's family nests under its own name.
  std::string q_net() const { return algo_.quantiles ? "quantile_net" : "q_net"; }
  double qrdqn_adam_eps() const {
    const Json batch = scalar_json(config_["batch_size"]);
    return 0.01 / (batch.is_number_integer() ? batch.get<double>() : 32.0);  // QR-DQN's default
  }
  void add_qrdqn_kwargs(PolicyKwargs& kwargs) const {
    const std::vector<int> widths = sb3_layer_widths(tensors_, "quantile_net.");
    const int64_t actions = model_.env->action_space().n();
    if (widths.empty() || actions <= 0) fail("its quantile network has no output layer");
    kwargs.plain["n_quantiles"] = widths.back() / actions;
    // QR-DQN's __init__ sets Adam with eps 0.01 / batch_size (sb3_contrib/qrdqn/qrdqn.py).
    kwargs.classes.emplace_back("optimizer_class", ClassRef{"torch.optim.adam", "Adam"});
    kwargs.plain["optimizer_kwargs"] = {{"eps", qrdqn_adam_eps()}};
  }

  bool flag(const char* name, bool fallback) const {
    const Json value = scalar_json(config_[name]);
    return value.is_boolean() ? value.get<bool>() : fallback;
  }
  bool uses_sde() const { return flag("use_sde", false); }
  bool uses_rms_prop() const { return id_ == "A2C" && flag("use_rms_prop", true); }
  double rms_prop_eps() const {
    const Json value = scalar_json(config_["rms_prop_eps"]);
    return value.is_number() ? value.get<double>() : 1e-5;
  }

  // A schedule's value now: a number, or rl-zoo's lin_<initial> as its initial value.
  std::optional<double> schedule_value(const std::string& name) {
    const Json value = scalar_json(config_[name]);
    if (value.is_number()) return value.get<double>();
    if (!value.is_string()) return std::nullopt;
    try {
      const Schedule schedule = Schedule::parse(value.get<std::string>());
      notes_.push_back(name + " '" + quoted_text(value.get<std::string>()) +
                       "' is written as its initial value " +
                       python_float_repr(schedule.initial()) +
                       ": SB3's file would hold its schedule as a pickled function");
      return schedule.initial();
    } catch (const std::invalid_argument&) {
      return std::nullopt;
    }
  }

  // Read once (data's learning_rate and every optimizer's lr): a schedule's note is said once.
  double learning_rate() {
    if (!learning_rate_) {
      const std::optional<double> lr = schedule_value("learning_rate");
      learning_rate_ = lr ? *lr : algo_.default_learning_rate;
    }
    return *learning_rate_;
  }

  void add_hyperparameter(Json& data, const std::string& name) {
    const YAML::Node value = config_[name];
    if (!value) return;
    if (name == "learning_rate") {
      data[name] = learning_rate();
    } else if (name == "clip_range" || name == "clip_range_vf") {
      const std::optional<double> v = schedule_value(name);
      data[name] = v ? Json(*v) : Json(nullptr);
    } else if (name == "train_freq") {
      data[name] = train_freq(value);
    } else if (name == "target_entropy" && scalar_json(value).is_string()) {
      // SB3 keeps the number "auto" stands for (sac.py _setup_model: -prod(action shape)),
      // and computes it from the env, which a file loaded without one does not have.
      data[name] = -static_cast<double>(model_.env->action_space().flat_dim());
    } else if (value.IsScalar() || value.IsNull()) {
      data[name] = scalar_json(value);
    }
  }

  // An int (steps) or [n, "step" | "episode"]: a pickled tuple, which SB3's
  // _convert_train_freq turns into its TrainFreq.
  Json train_freq(const YAML::Node& value) const {
    int64_t n = 1;
    std::string unit = "step";
    if (value.IsSequence() && value.size() == 2) {
      n = value[0].as<int64_t>();
      unit = value[1].as<std::string>();
    } else {
      n = value.as<int64_t>();
    }
    if (unit != "step" && unit != "episode") fail("train_freq unit '" + quoted_text(unit) + "'");
    PickleWriter p(kDataProtocol);
    p.mark();
    p.integer(n);
    p.text(unit);
    p.tuple_from_mark();
    return serialized("<class 'tuple'>", p.finish());
  }

  // A tensor of SB3's policy module (its state_dict); the others are attributes of the
  // algorithm that `data` or pytorch_variables.pth hold (check_policy said which).
  bool is_policy_tensor(const std::string& name) const {
    static const std::map<Family, std::vector<std::string>> prefixes = {
        {Family::kActorCritic,
         {"mlp_extractor.", "action_net.", "value_net.", "log_std", "features_extractor.",
          "pi_features_extractor.", "vf_features_extractor.",
          // RecurrentPPO's: the LSTMs and the critic's Linear (sb3_contrib/common/recurrent)
          "lstm_actor.", "lstm_critic.", "critic."}},
        {Family::kDqn, {"q_net.", "q_net_target.", "quantile_net.", "quantile_net_target."}},
        {Family::kSac, {"actor.", "critic.", "critic_target."}},
        {Family::kTd3, {"actor.", "actor_target.", "critic.", "critic_target."}}};
    for (const std::string& prefix : prefixes.at(algo_.family))
      if (name.starts_with(prefix)) return true;
    return false;
  }

  // policy.pth and the optimizers' and variables' files of the algorithm's
  // _get_torch_save_params.
  void write_tensors(ZipMembers& members) {
    std::vector<std::pair<std::string, const Tensor*>> policy;
    std::map<std::string, std::string> renamed;  // DQN: q_net.0.weight -> q_net.q_net.0.weight
    for (const auto& [name, tensor] : tensors_) {
      if (!is_policy_tensor(name)) continue;
      std::string sb3_name = name;
      for (const std::string& owner : {q_net() + ".", q_net() + "_target."})
        if (algo_.family == Family::kDqn && name.starts_with(owner) &&
            !name.starts_with(owner + "features_extractor."))
          sb3_name = owner + q_net() + "." + name.substr(owner.size());
      policy.emplace_back(renamed[name] = sb3_name, &tensor);
    }
    const auto unique_parameters = static_cast<int64_t>(policy.size());
    // SB3's ActorCriticPolicy names its extractors three times in its state_dict:
    // features_extractor is pi_features_extractor, and vf_features_extractor too when shared.
    if ((writes_cnn() || writes_combined_cnn()) && algo_.family == Family::kActorCritic)
      for (const auto& [name, tensor] : tensors_) {
        if (name.starts_with("features_extractor."))
          for (const char* copy : {"pi_", "vf_"}) policy.emplace_back(copy + name, &tensor);
        if (name.starts_with("pi_features_extractor."))
          policy.emplace_back(name.substr(strlen("pi_")), &tensor);
      }
    members["policy.pth"] = torch_save_state_dict(policy);
    const double lr = learning_rate();
    const auto count = [&](const std::string& prefix) {
      int64_t n = 0;
      for (const auto& [name, sb3_name] : renamed) n += sb3_name.starts_with(prefix) ? 1 : 0;
      return n;
    };
    switch (algo_.family) {
      case Family::kActorCritic:
        members["policy.optimizer.pth"] = optimizer_file(
            uses_rms_prop() ? rmsprop_group(lr, rms_prop_eps()) : adam_group(lr, 1e-5),
            unique_parameters);
        members["pytorch_variables.pth"] = torch_save_state_dict({});
        return;
      case Family::kDqn:
        // Since SB3 2.4 the optimizer holds the online network only.
        members["policy.optimizer.pth"] = optimizer_file(
            adam_group(lr, algo_.quantiles ? qrdqn_adam_eps() : 1e-8), count(q_net() + "."));
        members["pytorch_variables.pth"] = torch_save_state_dict({});
        return;
      case Family::kSac:
        members["actor.optimizer.pth"] = optimizer_file(adam_group(lr, 1e-8), count("actor."));
        members["critic.optimizer.pth"] = optimizer_file(
            adam_group(lr, 1e-8),
            count("critic.") -
                (critic_optimizer_skips_extractor() ? count("critic.features_extractor.") : 0));
        write_entropy_coefficient(members, lr);
        return;
      case Family::kTd3:
        members["actor.optimizer.pth"] = optimizer_file(adam_group(lr, 1e-8), count("actor."));
        members["critic.optimizer.pth"] = optimizer_file(adam_group(lr, 1e-8), count("critic."));
        members["pytorch_variables.pth"] = torch_save_state_dict({});
        return;
    }
  }

  // SAC: a learned coefficient is log_ent_coef with its own optimizer; a fixed one
  // ent_coef_tensor (stable_baselines3/sac/sac.py _setup_model, _get_torch_save_params).
  void write_entropy_coefficient(ZipMembers& members, double lr) {
    const Json configured = scalar_json(config_["ent_coef"]);
    const bool learned =  // SB3's default is "auto"
        configured.is_null() ||
        (configured.is_string() && configured.get<std::string>().starts_with("auto"));
    const auto found = tensors_.find("log_ent_coef");
    if (learned && found == tensors_.end()) fail("its learned ent_coef has no log_ent_coef");
    if (learned) {
      Tensor log_ent_coef = found->second;
      log_ent_coef.shape = {1};  // th.log(th.ones(1))
      members["pytorch_variables.pth"] = torch_save_state_dict({{"log_ent_coef", &log_ent_coef}});
      members["ent_coef_optimizer.pth"] = optimizer_file(adam_group(lr, 1e-8), 1);
      return;
    }
    if (!configured.is_number()) fail("its ent_coef is neither learned nor a number");
    const float value = static_cast<float>(configured.get<double>());
    Tensor tensor;  // th.tensor(float(ent_coef)): 0-d
    tensor.dtype = DType::kFloat32;
    tensor.bytes.resize(sizeof value);
    std::memcpy(tensor.bytes.data(), &value, sizeof value);
    if (const auto saved = tensors_.find("ent_coef_tensor"); saved != tensors_.end() &&
                                                             saved->second.numel() == 1 &&
                                                             saved->second.dtype == DType::kFloat32)
      tensor.bytes = saved->second.bytes;
    members["pytorch_variables.pth"] = torch_save_state_dict({{"ent_coef_tensor", &tensor}});
  }

  const LoadedModel& model_;
  const Sb3Algorithm& algo_;
  std::string id_;
  bool cnn_ = false;           // the model has a NatureCNN (features_extractor.cnn.*)
  bool combined_cnn_ = false;  // ... per image key (features_extractor.extractors.<k>.cnn.*)
  YAML::Node config_;
  TensorMap tensors_;
  std::vector<std::string> notes_;
  std::optional<double> learning_rate_;  // learning_rate()
};

}  // namespace sb3_writer

using sb3_writer::sb3_algorithm;
using sb3_writer::Sb3Algorithm;
using sb3_writer::Sb3Writer;

Sb3ModelExport sb3_model_export(const LoadedModel& model) {
  const Sb3Algorithm* algo = sb3_algorithm(model.file.meta.algorithm);
  if (!algo)
    throw RuntimeFailure("cannot write " + model.file.path +
                         " as an SB3 model file: its algorithm " +
                         quoted_text(model.file.meta.algorithm) +
                         " is not one of SB3's (PPO, A2C, DQN, SAC, TD3, DDPG) or "
                         "sb3-contrib's this writer writes (QRDQN, TQC, TRPO, MaskablePPO, "
                         "RecurrentPPO)");
  return Sb3Writer(model, *algo).write();
}

}  // namespace rlrun

#include "rlrun/runtime/io/sb3/sb3_model_file.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cstring>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>

#include "rlrun/core/base64.hpp"
#include "rlrun/core/errors.hpp"
#include "rlrun/core/pickle_reader.hpp"
#include "rlrun/core/quoted_text.hpp"
#include "rlrun/core/torch_state_dict.hpp"
#include "rlrun/core/zip_reader.hpp"
#include "rlrun/runtime/io/non_finite_check.hpp"
#include "rlrun/runtime/io/sb3/sb3_net_arch.hpp"
#include "rlrun/runtime/io/sb3/sb3_spaces.hpp"
#include "rlrun/runtime/io/sb3/sb3_vec_normalize.hpp"

namespace rlrun {

namespace {

using Json = nlohmann::json;

// `data` is a few KiB (a few MiB with a large _last_obs); policy.pth holds the weights.
constexpr uint64_t kMaxDataBytes = uint64_t{64} << 20;
// The zoo's largest policies (Atari CnnPolicy) are under 20 MiB.
constexpr uint64_t kMaxPolicyBytes = uint64_t{256} << 20;
constexpr uint64_t kMaxVariablesBytes = uint64_t{1} << 20;

// What the policy class says: which family of algorithms (sb3-contrib's QR-DQN and TQC are
// DQN's and SAC's with quantile heads).
enum class PolicyFamily { kActorCritic, kDqn, kQrDqn, kSac, kTqc, kTd3 };

bool has_sde(PolicyFamily family) {
  return family == PolicyFamily::kActorCritic || family == PolicyFamily::kSac ||
         family == PolicyFamily::kTqc;
}
bool entropy_regularized(PolicyFamily family) {
  return family == PolicyFamily::kSac || family == PolicyFamily::kTqc;
}

class Sb3Reader {
 public:
  Sb3Reader(const std::string& path, const std::string& env_id, const YAML::Node& env_section)
      : path_(path), env_id_(env_id), env_section_(env_section), archive_(path) {}

  ModelFile read() {
    data_ = parse_data();
    const PolicyFamily family = policy_family();
    if (uses_sde() && !has_sde(family)) fail("it says use_sde=True for a policy without gSDE");
    // A CnnPolicy's file holds the space after SB3's VecTransposeImage (channels first); the
    // env, and rlrun's CnnPolicy (which transposes as SB3 does), see it channels last.
    // A Dict's image keys likewise (MultiInputPolicy: CombinedExtractor's NatureCNNs).
    const Space observation_space = cnn_ ? channels_last(space("observation_space"))
                                         : channels_last_dict_images(space("observation_space"));
    const Space action_space = space("action_space");
    ModelFile model;
    model.path = path_;
    model.tensors = policy_tensors(family);
    model.meta.algorithm = algorithm(family);
    model.meta.env_id = env_id_;
    model.meta.observation_space = observation_space.describe();
    model.meta.action_space = action_space.describe();
    // No wrappers: the env's spaces are the agent's (how it draws is not recorded).
    model.meta.env_spaces = EnvSpaces{observation_space, action_space, 1, {}};
    if (data_.contains("num_timesteps") && data_["num_timesteps"].is_number_integer())
      model.meta.num_timesteps = data_["num_timesteps"].get<int64_t>();
    // VecNormalize's statistics beside the model become rlrun's env.normalize, frozen in play.
    std::optional<NormalizeSetting> normalize;
    if (const std::optional<std::string> pkl = find_sb3_vec_normalize(path_)) {
      Sb3VecNormalize vec_normalize = read_sb3_vec_normalize(*pkl, observation_space.flat_dim());
      normalize = vec_normalize.setting;
      model.wrapper_statistics = std::move(vec_normalize.statistics);
      // SB3 keeps the env's space; the policy of rlrun's env.normalize sees the normalised one
      // (wrappers/normalize_observation.cpp).
      if (normalize->norm_obs && observation_space.is_box()) {
        const float clip = static_cast<float>(normalize->clip_obs);
        model.meta.observation_space =
            Space::box(-clip, clip, observation_space.shape()).describe();
      }
    }
    model.config_yaml =
        config_yaml(family, model.meta.algorithm, model.tensors, action_space, normalize);
    const std::string problem = describe_non_finite(model.tensors);
    if (!problem.empty()) fail(problem);
    return model;
  }

 private:
  [[noreturn]] void fail(const std::string& why) const {
    throw RuntimeFailure(path_ + ": " + why + " (an SB3 model file: docs/sb3_models.md)");
  }

  Json parse_data() {
    const ZipEntry* entry = archive_.find("data");
    if (!entry) fail("no `data` member");
    const std::vector<uint8_t> bytes = archive_.read(*entry, kMaxDataBytes);
    Json data = Json::parse(bytes.begin(), bytes.end(), nullptr, /*allow_exceptions=*/false);
    if (!data.is_object()) fail("its `data` member is not a JSON object");
    return data;
  }

  // A cloudpickled entry of `data`: {":type:": ..., ":serialized:": base64, ...}.
  PickleDocument pickled(const char* key, const PickleGlobalFilter& allowed) const {
    const auto found = data_.find(key);
    if (found == data_.end() || !found->is_object() || !found->contains(":serialized:") ||
        !(*found)[":serialized:"].is_string())
      fail(std::string("its `data` has no serialized '") + key + "'");
    const std::optional<std::vector<uint8_t>> bytes =
        decode_base64((*found)[":serialized:"].get_ref<const std::string&>());
    if (!bytes) fail(std::string("'") + key + "' in `data` is not base64");
    return read_pickle(bytes->data(), bytes->size(), path_ + ": data['" + key + "']", allowed);
  }

  PolicyFamily policy_family() {
    // The class is only compared with SB3's names, never imported: any SB3 or sb3-contrib name
    // may appear, nothing else.
    const PickleDocument document =
        pickled("policy_class", [](const std::string& module, const std::string&) {
          return module.starts_with("stable_baselines3.") || module.starts_with("sb3_contrib.");
        });
    const PickleValue& c = document.root();
    if (c.kind != PickleKind::kGlobal) fail("its policy_class is not a class");
    // SB3's CnnPolicy of each algorithm: its MlpPolicy over a NatureCNN (one shared by actor
    // and critic for PPO and A2C, stable_baselines3/common/policies.py ActorCriticCnnPolicy;
    // the off-policy ones' CnnPolicy in their policies.py, each network with its own).
    static const std::map<std::pair<std::string, std::string>, PolicyFamily> cnn_policies = {
        {{"stable_baselines3.common.policies", "ActorCriticCnnPolicy"}, PolicyFamily::kActorCritic},
        {{"stable_baselines3.dqn.policies", "CnnPolicy"}, PolicyFamily::kDqn},
        {{"stable_baselines3.sac.policies", "CnnPolicy"}, PolicyFamily::kSac},
        {{"stable_baselines3.td3.policies", "CnnPolicy"}, PolicyFamily::kTd3},
        {{"sb3_contrib.qrdqn.policies", "CnnPolicy"}, PolicyFamily::kQrDqn},
        {{"sb3_contrib.tqc.policies", "CnnPolicy"}, PolicyFamily::kTqc},
    };
    if (const auto found = cnn_policies.find({c.module, c.text}); found != cnn_policies.end()) {
      cnn_ = true;
      return found->second;
    }
    static const std::map<std::pair<std::string, std::string>, PolicyFamily> known = {
        {{"stable_baselines3.common.policies", "ActorCriticPolicy"}, PolicyFamily::kActorCritic},
        {{"stable_baselines3.common.policies", "MultiInputActorCriticPolicy"},
         PolicyFamily::kActorCritic},
        {{"stable_baselines3.dqn.policies", "DQNPolicy"}, PolicyFamily::kDqn},
        {{"stable_baselines3.dqn.policies", "MultiInputPolicy"}, PolicyFamily::kDqn},
        {{"stable_baselines3.sac.policies", "SACPolicy"}, PolicyFamily::kSac},
        {{"stable_baselines3.sac.policies", "MultiInputPolicy"}, PolicyFamily::kSac},
        {{"stable_baselines3.td3.policies", "TD3Policy"}, PolicyFamily::kTd3},
        {{"stable_baselines3.td3.policies", "MultiInputPolicy"}, PolicyFamily::kTd3},
        {{"sb3_contrib.qrdqn.policies", "QRDQNPolicy"}, PolicyFamily::kQrDqn},
        {{"sb3_contrib.qrdqn.policies", "MultiInputPolicy"}, PolicyFamily::kQrDqn},
        {{"sb3_contrib.tqc.policies", "TQCPolicy"}, PolicyFamily::kTqc},
        {{"sb3_contrib.tqc.policies", "MultiInputPolicy"}, PolicyFamily::kTqc},
    };
    // sb3-contrib's MaskablePPO and RecurrentPPO: PPO's actor-critic (the same tensor names),
    // the second with its LSTMs in front (sb3_contrib/common/{maskable,recurrent}/policies.py).
    static const std::map<std::pair<std::string, std::string>, std::string> ppo_variants = {
        {{"sb3_contrib.common.maskable.policies", "MaskableActorCriticPolicy"}, "MaskablePPO"},
        {{"sb3_contrib.common.maskable.policies", "MaskableMultiInputActorCriticPolicy"},
         "MaskablePPO"},
        {{"sb3_contrib.common.recurrent.policies", "RecurrentActorCriticPolicy"}, "RecurrentPPO"},
        {{"sb3_contrib.common.recurrent.policies", "RecurrentMultiInputActorCriticPolicy"},
         "RecurrentPPO"},
        {{"sb3_contrib.common.maskable.policies", "MaskableActorCriticCnnPolicy"}, "MaskablePPO"},
        {{"sb3_contrib.common.recurrent.policies", "RecurrentActorCriticCnnPolicy"},
         "RecurrentPPO"},
    };
    if (const auto variant = ppo_variants.find({c.module, c.text}); variant != ppo_variants.end()) {
      ppo_variant_ = variant->second;
      cnn_ = c.text.find("Cnn") != std::string::npos;
      return PolicyFamily::kActorCritic;
    }
    if (c.text.find("Cnn") != std::string::npos)
      fail("its policy is " + c.module + "." + c.text +
           ": rlrun reads the CnnPolicy of PPO, A2C, DQN, SAC, TD3, DDPG, and sb3-contrib's "
           "QR-DQN, TQC, TRPO, MaskablePPO and RecurrentPPO (CnnLstmPolicy)");
    const auto found = known.find({c.module, c.text});
    if (found == known.end())
      fail("its policy class is " + c.module + "." + c.text +
           "; rlrun reads the MlpPolicy and MultiInputPolicy of PPO, A2C, DQN, SAC, TD3, DDPG, "
           "and sb3-contrib's QR-DQN, TQC, TRPO, MaskablePPO and RecurrentPPO (MlpLstmPolicy)");
    return found->second;
  }

  std::string algorithm(PolicyFamily family) const {
    switch (family) {
      case PolicyFamily::kActorCritic:
        if (!ppo_variant_.empty()) return ppo_variant_;
        // sb3-contrib's TRPO keeps SB3's ActorCriticPolicy; its conjugate-gradient settings
        // tell it apart (sb3_contrib/trpo/trpo.py).
        if (data_.contains("cg_max_steps")) return "TRPO";
        return data_.contains("clip_range") ? "PPO" : "A2C";
      case PolicyFamily::kDqn: return "DQN";
      case PolicyFamily::kQrDqn: return "QRDQN";
      case PolicyFamily::kSac: return "SAC";
      case PolicyFamily::kTqc: return "TQC";
      case PolicyFamily::kTd3: {
        // DDPG is TD3 with policy_delay=1, target_policy_noise=0.1, target_noise_clip=0
        // (stable_baselines3/ddpg/ddpg.py).
        const bool ddpg = data_.value("policy_delay", Json()) == 1 &&
                          data_.value("target_noise_clip", Json()) == 0.0;
        return ddpg ? "DDPG" : "TD3";
      }
    }
    return "";
  }

  Space space(const char* key) const {
    const PickleDocument document = pickled(key, is_sb3_space_global);
    return sb3_space(document.root(), path_ + ": data['" + key + "']");
  }

  TensorMap torch_member(const char* name, uint64_t max_bytes, bool required) const {
    const ZipEntry* entry = archive_.find(name);
    if (!entry) {
      if (required) fail(std::string("no ") + name + " member");
      return {};
    }
    return read_torch_tensors(archive_.read(*entry, max_bytes), archive_.describe(*entry),
                              max_bytes);
  }

  // DQNPolicy.q_net is a QNetwork whose Sequential is also named q_net (QR-DQN's quantile_net
  // likewise): q_net.q_net.0.weight is rlrun's q_net.0.weight. Every other name is rlrun's.
  static std::string rlrun_name(PolicyFamily family, const std::string& name) {
    const char* net = family == PolicyFamily::kDqn     ? "q_net"
                      : family == PolicyFamily::kQrDqn ? "quantile_net"
                                                       : nullptr;
    if (!net) return name;
    for (const std::string& owner : {std::string(net), std::string(net) + "_target"}) {
      const std::string nested = owner + "." + net + ".";
      if (name.starts_with(nested)) return owner + "." + name.substr(nested.size());
    }
    return name;
  }

  bool uses_sde() const { return data_.contains("use_sde") && data_["use_sde"] == true; }

  // SB3's state_dict under rlrun's names (algos/*: save/load write SB3's names).
  TensorMap policy_tensors(PolicyFamily family) const {
    TensorMap sb3 = torch_member("policy.pth", kMaxPolicyBytes, true);
    if (family == PolicyFamily::kActorCritic) drop_extractor_aliases(sb3);
    TensorMap out;
    for (auto& [name, tensor] : sb3) {
      if (tensor.dtype != DType::kFloat32)
        fail("tensor '" + quoted_text(name) + "' is not float32");
      out[rlrun_name(family, name)] = std::move(tensor);
    }
    if (entropy_regularized(family)) {
      // SB3 before 1.0 named the file tensors.pth.
      TensorMap variables = torch_member("pytorch_variables.pth", kMaxVariablesBytes, false);
      if (variables.empty()) variables = torch_member("tensors.pth", kMaxVariablesBytes, false);
      if (variables.count("log_ent_coef")) out["log_ent_coef"] = variables["log_ent_coef"];
    }
    return out;
  }

  // An attribute of policy_kwargs: SB3 writes the dict as JSON, or (when it holds classes) as
  // a serialized entry beside which each attribute is JSON or its str().
  std::optional<Json> policy_kwarg(const char* name) const {
    const auto kwargs = data_.find("policy_kwargs");
    if (kwargs == data_.end() || !kwargs->is_object() || !kwargs->contains(name))
      return std::nullopt;
    return (*kwargs)[name];
  }

  // "<class 'torch.nn.modules.activation.ReLU'>" -> "relu".
  std::string activation(PolicyFamily family) const {
    const std::optional<Json> value = policy_kwarg("activation_fn");
    if (!value) return family == PolicyFamily::kActorCritic ? "tanh" : "relu";
    static const std::map<std::string, std::string> names = {{"Tanh", "tanh"},
                                                             {"ReLU", "relu"},
                                                             {"ELU", "elu"},
                                                             {"LeakyReLU", "leaky_relu"},
                                                             {"GELU", "gelu"}};
    const std::string text = value->is_string() ? value->get<std::string>() : "";
    const std::string prefix = "<class 'torch.nn.modules.activation.";
    if (text.starts_with(prefix) && text.ends_with("'>")) {
      const auto found = names.find(text.substr(prefix.size(), text.size() - prefix.size() - 2));
      if (found != names.end()) return found->second;
    }
    fail("its activation_fn '" + quoted_text(value->dump()) +
         "' is not one rlrun has (torch.nn Tanh, ReLU, ELU, LeakyReLU, GELU)");
  }

  // SB3's ActorCriticPolicy names its extractors three times (stable_baselines3/common/
  // policies.py): features_extractor, and pi_features_extractor (the same module) and
  // vf_features_extractor (the same one again with share_features_extractor=True, else its
  // own). rlrun names them as its own CnnPolicy does: features_extractor when shared, else
  // pi_features_extractor and vf_features_extractor.
  void drop_extractor_aliases(TensorMap& tensors) const {
    const auto same = [&](const std::string& a, const std::string& b) {
      const auto x = tensors.find(a), y = tensors.find(b);
      return x != tensors.end() && y != tensors.end() && x->second.shape == y->second.shape &&
             x->second.bytes == y->second.bytes;
    };
    std::vector<std::string> suffixes;
    for (const auto& [name, tensor] : tensors)
      if (name.starts_with("features_extractor."))
        suffixes.push_back(name.substr(strlen("features_extractor.")));
    if (suffixes.empty()) return;  // no weights: a flatten extractor
    bool shared = true;
    for (const std::string& suffix : suffixes) {
      if (!same("features_extractor." + suffix, "pi_features_extractor." + suffix))
        fail("its pi_features_extractor is not its features_extractor (SB3 makes them one)");
      shared = shared && same("features_extractor." + suffix, "vf_features_extractor." + suffix);
    }
    const auto erase = [&](const std::string& prefix) {
      std::erase_if(tensors, [&](const auto& entry) { return entry.first.starts_with(prefix); });
    };
    if (shared) {
      erase("pi_features_extractor.");
      erase("vf_features_extractor.");
    } else {
      erase("features_extractor.");
    }
  }

  // A CnnPolicy, or a MultiInputPolicy whose CombinedExtractor has a NatureCNN for an image key.
  bool has_cnn(const TensorMap& tensors) const { return cnn_ || sb3_has_combined_cnn(tensors); }

  // SB3's transposed image space (C, H, W) back to the env's (H, W, C).
  Space channels_last(const Space& chw) const {
    if (!chw.is_box() || chw.shape().size() != 3 || chw.dtype() != BoxDtype::kUint8)
      fail("its CnnPolicy's observation space is not a uint8 image (C, H, W)");
    return channels_last_image(chw);
  }

  void check_extractor() const {
    const std::optional<Json> value = policy_kwarg("features_extractor_class");
    if (!value) return;  // SB3's default: FlattenExtractor, or NatureCNN for a CnnPolicy
    const std::string text = value->is_string() ? value->get<std::string>() : value->dump();
    if (cnn_) {
      if (text.ends_with("torch_layers.NatureCNN'>")) return;
      fail("its CnnPolicy's features extractor is '" + quoted_text(text) +
           "'; rlrun reads SB3's NatureCNN");
    }
    for (const char* ok : {"torch_layers.FlattenExtractor'>", "torch_layers.CombinedExtractor'>"})
      if (text.ends_with(ok)) return;
    fail("its features extractor is '" + quoted_text(text) +
         "'; rlrun reads SB3's FlattenExtractor and CombinedExtractor");
  }

  // The networks' sizes, read off the weights.
  YAML::Node policy_node(PolicyFamily family, const TensorMap& tensors,
                         const Space& action_space) const {
    YAML::Node policy;
    YAML::Node net_arch;
    switch (family) {
      case PolicyFamily::kActorCritic:
        net_arch["pi"] = sb3_layer_widths(tensors, "mlp_extractor.policy_net.");
        net_arch["vf"] = sb3_layer_widths(tensors, "mlp_extractor.value_net.");
        if (has_cnn(tensors)) add_nature_cnn(tensors, "", policy);
        if (ppo_variant_ == "RecurrentPPO") add_lstm(tensors, policy);
        break;
      case PolicyFamily::kDqn:
        net_arch = sb3_hidden_widths(tensors, "q_net.");
        if (has_cnn(tensors)) add_nature_cnn(tensors, "q_net.", policy);
        break;
      case PolicyFamily::kQrDqn: {
        net_arch = sb3_hidden_widths(tensors, "quantile_net.");
        if (has_cnn(tensors)) add_nature_cnn(tensors, "quantile_net.", policy);
        // The head outputs n_quantiles per action.
        const std::vector<int> all = sb3_layer_widths(tensors, "quantile_net.");
        const int actions = action_space.is_discrete() ? static_cast<int>(action_space.n()) : 0;
        if (all.empty() || actions <= 0 || all.back() % actions != 0)
          fail("its quantile network does not fit its action space");
        policy["n_quantiles"] = all.back() / actions;
        break;
      }
      case PolicyFamily::kSac:
      case PolicyFamily::kTqc:
      case PolicyFamily::kTd3: {
        net_arch["pi"] = family == PolicyFamily::kTd3
                             ? sb3_hidden_widths(tensors, "actor.mu.")
                             : sb3_layer_widths(tensors, "actor.latent_pi.");
        net_arch["qf"] = sb3_hidden_widths(tensors, "critic.qf0.");
        policy["n_critics"] = sb3_critic_count(tensors);
        const std::vector<int> critic = sb3_layer_widths(tensors, "critic.qf0.");
        if (family == PolicyFamily::kTqc && !critic.empty()) policy["n_quantiles"] = critic.back();
        if (has_cnn(tensors)) add_nature_cnn(tensors, "actor.", policy);
        break;
      }
    }
    policy["net_arch"] = net_arch;
    policy["activation_fn"] = activation(family);
    if (const std::optional<Json> v = policy_kwarg("normalize_images"); v && v->is_boolean())
      policy["normalize_images"] = v->get<bool>();
    return policy;
  }

  // NatureCNN's output width, read off its linear layer (the convolutions are NatureCNN's own;
  // loading the tensors checks their shapes against the network rlrun builds).
  // A CnnPolicy's NatureCNN (features_dim), or a MultiInputPolicy's CombinedExtractor with a
  // NatureCNN per image key (cnn_output_dim), each width read off the first extractor's linear
  // layer. `network`: where that extractor is, "" for the actor-critic's own.
  void add_nature_cnn(const TensorMap& tensors, const std::string& network,
                      YAML::Node& policy) const {
    // An actor-critic's separate extractors are pi_/vf_features_extractor (drop_extractor_aliases).
    const bool separate =
        network.empty() && std::any_of(tensors.begin(), tensors.end(), [](const auto& t) {
          return t.first.starts_with("pi_features_extractor.");
        });
    const std::string owner = (separate ? "pi_" : network) + "features_extractor.";
    const std::string combined = owner + "extractors.";
    auto linear = tensors.end();
    for (auto it = tensors.begin(); it != tensors.end(); ++it)
      if (it->first.ends_with(".linear.0.weight") &&
          (it->first == owner + "linear.0.weight" || it->first.starts_with(combined))) {
        linear = it;
        break;
      }
    if (linear == tensors.end() || linear->second.shape.size() != 2)
      fail("its policy's NatureCNN has no linear layer (" + owner + "linear.0.weight)");
    const bool per_key = linear->first.starts_with(combined);
    policy["features_extractor_class"] = per_key ? "CombinedExtractor" : "NatureCNN";
    policy[per_key ? "cnn_output_dim" : "features_dim"] = static_cast<int>(linear->second.shape[0]);
    // SB3's default: shared by PPO's actor and critic, separate for the off-policy ones.
    const std::optional<Json> shared = policy_kwarg("share_features_extractor");
    if (network.empty())
      policy["share_features_extractor"] = !separate;
    else if (shared && shared->is_boolean())
      policy["share_features_extractor"] = shared->get<bool>();
  }

  // RecurrentPPO's LSTMs, read off the weights as torch.nn.LSTM names them (weight_hh_l<k> is
  // 4*hidden x hidden): the actor's layers; the critic has its own LSTM (lstm_critic:
  // enable_critic_lstm), a Linear (critic: neither), or reads the actor's (shared_lstm).
  // Each layer's weight_hh must be 4*hidden x hidden: the network rlrun builds holds what the
  // file holds, so a file cannot declare a hidden size its weights do not pay for (a [1, H]
  // tensor naming H = 65536 would make rlrun allocate 4*H*H floats; docs/security.md).
  void add_lstm(const TensorMap& tensors, YAML::Node& policy) const {
    const auto hh = tensors.find("lstm_actor.weight_hh_l0");
    if (hh == tensors.end() || hh->second.shape.size() != 2)
      fail("its recurrent policy has no lstm_actor.weight_hh_l0");
    const int64_t hidden = hh->second.shape[1];
    int layers = 0;
    while (tensors.count("lstm_actor.weight_ih_l" + std::to_string(layers))) ++layers;
    for (const char* lstm : {"lstm_actor", "lstm_critic"})
      for (int layer = 0; layer < layers; ++layer) {
        const std::string name = std::string(lstm) + ".weight_hh_l" + std::to_string(layer);
        const auto found = tensors.find(name);
        if (found == tensors.end()) continue;  // no critic LSTM
        if (found->second.shape != std::vector<int64_t>{4 * hidden, hidden})
          fail("its " + name + " is not 4*hidden x hidden (hidden " + std::to_string(hidden) +
               ", from lstm_actor.weight_hh_l0)");
      }
    policy["lstm_hidden_size"] = static_cast<int>(hidden);
    policy["n_lstm_layers"] = layers;
    const bool critic_lstm = tensors.count("lstm_critic.weight_hh_l0") > 0;
    policy["enable_critic_lstm"] = critic_lstm;
    policy["shared_lstm"] = !critic_lstm && !tensors.count("critic.weight");
  }

  // gSDE (use_sde=True): the policy_kwargs that shape it (stable_baselines3/common/
  // distributions.py StateDependentNoiseDistribution; SAC's Actor clip_mean), SB3's defaults
  // where the file has none.
  void add_sde(PolicyFamily family, YAML::Node& algo, YAML::Node& policy) const {
    algo["use_sde"] = true;
    if (data_.contains("sde_sample_freq") && data_["sde_sample_freq"].is_number_integer())
      algo["sde_sample_freq"] = data_["sde_sample_freq"].get<int64_t>();
    for (const char* flag : {"full_std", "use_expln"})
      if (const std::optional<Json> v = policy_kwarg(flag); v && v->is_boolean())
        policy[flag] = v->get<bool>();
    if (const std::optional<Json> v = policy_kwarg("log_std_init"); v && v->is_number())
      policy["log_std_init"] = v->get<double>();
    if (entropy_regularized(family)) {
      const std::optional<Json> v = policy_kwarg("clip_mean");
      policy["clip_mean"] = v && v->is_number() ? v->get<double>() : 2.0;  // SB3's Actor default
    }
  }

  std::string config_yaml(PolicyFamily family, const std::string& algo, const TensorMap& tensors,
                          const Space& action_space,
                          const std::optional<NormalizeSetting>& normalize) const {
    check_extractor();
    YAML::Node root;
    root["run"]["name"] = "sb3_model";
    root["env"]["id"] = env_id_;
    for (const char* key : {"kwargs", "wrappers", "max_episode_steps"})
      if (env_section_.IsMap() && env_section_[key]) root["env"][key] = env_section_[key];
    if (normalize) root["env"]["normalize"] = encode(*normalize);
    root["algo"]["id"] = algo;
    YAML::Node policy = policy_node(family, tensors, action_space);
    if (uses_sde()) {
      YAML::Node algo_node = root["algo"];
      add_sde(family, algo_node, policy);
    }
    if (entropy_regularized(family) && !tensors.count("log_ent_coef")) {
      const Json ent_coef = data_.value("ent_coef", Json());
      if (ent_coef.is_number()) root["algo"]["ent_coef"] = ent_coef.get<double>();
    }
    root["algo"]["policy"] = policy;
    YAML::Emitter out;
    out << root;
    return std::string(out.c_str()) + "\n";
  }

  std::string path_;
  std::string env_id_;
  YAML::Node env_section_;
  ZipReader archive_;
  Json data_;
  std::string ppo_variant_;  // "MaskablePPO" or "RecurrentPPO" for sb3-contrib's policy classes
  bool cnn_ = false;         // one of SB3's CnnPolicy classes
};

}  // namespace

bool is_sb3_model_file(const std::string& path) {
  try {
    const ZipReader archive(path);
    return archive.find("data") && archive.find("policy.pth") && !archive.find("meta.json");
  } catch (const RuntimeFailure&) {
    return false;
  }
}

ModelFile read_sb3_model(const std::string& path, const std::string& env_id,
                         const YAML::Node& env_section) {
  return Sb3Reader(path, env_id, env_section).read();
}

}  // namespace rlrun

#include "rlrun/runtime/workflows/zoo/zoo_policy.hpp"

#include <algorithm>
#include <utility>

#include "rlrun/nn/activation.hpp"
#include "rlrun/runtime/workflows/zoo/zoo_values.hpp"

namespace rlrun::zoo {

namespace {

bool listed(const std::vector<std::string>& names, const std::string& name) {
  return std::find(names.begin(), names.end(), name) != names.end();
}

class PolicyTranslation {
 public:
  PolicyTranslation(const ConfigNode& at, const std::vector<std::string>& keys,
                    const std::string& algorithm, std::vector<std::string>& notes)
      : at_(at), keys_(keys), algorithm_(algorithm), notes_(notes) {}

  YAML::Node translate(const PyValue& kwargs) {
    if (kwargs.kind != PyValue::Kind::kDict)
      fail("policy_kwargs must be a dict, found " + kwargs.describe());
    YAML::Node policy(YAML::NodeType::Map);
    for (const auto& [key, value] : kwargs.entries) {
      if (key == "net_arch") {
        policy[key] = net_arch(value);
      } else if (key == "activation_fn") {
        policy[key] = activation(value);
      } else if ((key == "share_features_extractor" || key == "normalize_images") &&
                 listed(keys_, key)) {
        // The policies' image switches (share_features_extractor: PPO and A2C).
        if (value.kind != PyValue::Kind::kBool)
          fail("policy_kwargs " + key + " must be True or False, found " + value.describe());
        policy[key] = to_yaml(value);
      } else if (key == "features_extractor_kwargs" && listed(keys_, "features_dim")) {
        // NatureCNN's one keyword: dict(features_dim=N).
        if (value.kind != PyValue::Kind::kDict || value.entries.size() != 1 ||
            value.entries[0].first != "features_dim")
          fail(
              "policy_kwargs features_extractor_kwargs: rlrun's NatureCNN reads "
              "dict(features_dim=N), found " +
              value.describe());
        policy["features_dim"] = to_yaml(value.entries[0].second);
      } else if (key == "squash_output" || key == "share_features_extractor" ||
                 key == "normalize_images") {
        no_effect(key, value);
      } else if (key == "optimizer_class") {
        // SB3's default optimizer of these algorithms is Adam (A2C: RMSprop via use_rms_prop).
        if (value.kind != PyValue::Kind::kName || !ends_with(value.text, "optim.Adam") ||
            algorithm_ == "A2C")
          fail("optimizer_class " + value.describe() + ": rlrun's " + algorithm_ +
               " uses SB3's default optimizer only (A2C: set use_rms_prop)");
        notes_.push_back("policy_kwargs optimizer_class=th.optim.Adam is " + algorithm_ +
                         "'s default optimizer");
      } else if (listed(keys_, key)) {
        if (value.kind == PyValue::Kind::kName || value.kind == PyValue::Kind::kDict)
          fail("policy_kwargs " + key + ": " + value.describe() + " is not a value rlrun reads");
        policy[key] = to_yaml(value);
      } else {
        fail("policy_kwargs key '" + key + "': rlrun's " + algorithm_ +
             " policy has no such setting" + did_you_mean(key, keys_) + " (it has: " + join(keys_) +
             ")");
      }
    }
    return policy;
  }

 private:
  [[noreturn]] void fail(const std::string& message) const { at_.fail(message); }

  static bool ends_with(const std::string& s, const std::string& tail) {
    return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
  }
  static std::string join(const std::vector<std::string>& v) {
    std::string s;
    for (const auto& x : v) s += (s.empty() ? "" : ", ") + x;
    return s;
  }

  YAML::Node layer_list(const PyValue& v, const std::string& what) const {
    if (v.kind != PyValue::Kind::kList)
      fail("policy_kwargs " + what + " must be a list of layer sizes, found " + v.describe());
    for (const PyValue& item : v.items)
      if (item.kind != PyValue::Kind::kNumber || !item.integral)
        fail("policy_kwargs " + what + ": layer sizes are integers, found " + item.describe());
    return to_yaml(v);
  }

  YAML::Node net_arch(const PyValue& v) const {
    // SB3 < 1.8 wrote separate networks as [dict(pi=..., vf=...)]; SB3 1.8 reads that the same
    // as dict(pi=..., vf=...) (with a deprecation warning).
    if (v.kind == PyValue::Kind::kList && v.items.size() == 1 &&
        v.items[0].kind == PyValue::Kind::kDict)
      return net_arch(v.items[0]);
    if (v.kind == PyValue::Kind::kList) {
      for (const PyValue& item : v.items)
        if (item.kind == PyValue::Kind::kDict)
          fail(
              "policy_kwargs net_arch: shared layers before dict(pi=..., vf=...) are gone since "
              "SB3 1.8 and rlrun has none; write net_arch=dict(pi=[...], vf=[...])");
      return layer_list(v, "net_arch");
    }
    if (v.kind != PyValue::Kind::kDict)
      fail("policy_kwargs net_arch must be a list or dict(pi=..., vf=.../qf=...), found " +
           v.describe());
    YAML::Node map(YAML::NodeType::Map);
    for (const auto& [key, sizes] : v.entries) {
      if (key != "pi" && key != "vf" && key != "qf")
        fail("policy_kwargs net_arch key '" + key + "': SB3 knows pi, vf and qf");
      map[key] = layer_list(sizes, "net_arch " + key);
    }
    map.SetStyle(YAML::EmitterStyle::Flow);
    return map;
  }

  YAML::Node activation(const PyValue& v) const {
    if (v.kind == PyValue::Kind::kName) {
      // th.nn.X and torch.nn.X are nn.X; nn/activation.hpp knows the nn.X spellings.
      std::string_view name = v.text;
      for (std::string_view module : {"th.", "torch."})
        if (name.starts_with(module)) name.remove_prefix(module.size());
      if (name.starts_with("nn."))
        if (const auto act = find_activation(name))
          return YAML::Node(std::string(activation_name(*act)));
    }
    fail("policy_kwargs activation_fn " + v.describe() +
         ": rlrun reads nn.Tanh, nn.ReLU, nn.ELU, nn.LeakyReLU and nn.GELU (also th.nn.X, "
         "torch.nn.X)");
  }

  void no_effect(const std::string& key, const PyValue& v) {
    if (key == "squash_output" && !(v.kind == PyValue::Kind::kBool && !v.boolean))
      fail("policy_kwargs squash_output=" + v.describe() +
           ": rlrun's on-policy Gaussian policies do not squash (SB3's default, False)");
    if (v.kind != PyValue::Kind::kBool)
      fail("policy_kwargs " + key + " must be True or False, found " + v.describe());
    notes_.push_back("policy_kwargs " + key + "=" + v.describe() +
                     " has no effect on an MLP policy (its features extractor is a flatten, "
                     "without parameters or images)");
  }

  const ConfigNode& at_;
  const std::vector<std::string>& keys_;
  const std::string& algorithm_;
  std::vector<std::string>& notes_;
};

}  // namespace

bool check_policy_name(const ConfigNode& policy, const std::string& algorithm) {
  const std::string name = policy.as_string();
  // sb3-contrib RecurrentPPO's policy_aliases: the same policies with an LSTM.
  const bool recurrent = algorithm == "RecurrentPPO";
  if (recurrent) {
    if (name == "MlpLstmPolicy" || name == "MultiInputLstmPolicy") return false;
    if (name == "CnnLstmPolicy") return true;
    policy.fail("policy '" + name +
                "': RecurrentPPO's policies are MlpLstmPolicy, CnnLstmPolicy and "
                "MultiInputLstmPolicy");
  }
  if (name == "MlpPolicy" || name == "MultiInputPolicy") return false;
  if (name == "CnnPolicy") {
    for (const char* with_cnn :
         {"PPO", "MaskablePPO", "A2C", "DQN", "QRDQN", "SAC", "TD3", "DDPG", "TQC"})
      if (algorithm == with_cnn) return true;
    policy.fail(
        "CnnPolicy: rlrun's convolutional policy (NatureCNN) is built for PPO, MaskablePPO, A2C, "
        "DQN, "
        "QRDQN, SAC, TD3, DDPG and TQC, not yet for " +
        algorithm);
  }
  policy.fail("policy '" + name +
              "': rlrun imports MlpPolicy and MultiInputPolicy only, not "
              "custom policy classes");
}

YAML::Node translate_policy_kwargs(const ConfigNode& policy_kwargs,
                                   const std::vector<std::string>& policy_keys,
                                   const std::string& algorithm, std::vector<std::string>& notes) {
  const PyValue kwargs = python_value(policy_kwargs, "policy_kwargs");
  return PolicyTranslation(policy_kwargs, policy_keys, algorithm, notes).translate(kwargs);
}

}  // namespace rlrun::zoo

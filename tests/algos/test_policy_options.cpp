// The policy / network options rl-zoo entries use (policy_kwargs), with SB3's semantics: net_arch
// as a list or a {pi, vf} / {pi, qf} map (algos/common/net_arch.hpp), activation_fn by name or
// torch class (algos/common/activation_config.hpp), ortho_init false.
#include <catch2/catch.hpp>
#include <cmath>
#include <string>
#include <vector>

#include "rlrun/algos/a2c/a2c.hpp"
#include "rlrun/algos/common/actor_critic_policy.hpp"
#include "rlrun/algos/ddpg/ddpg.hpp"
#include "rlrun/algos/dqn/dqn.hpp"
#include "rlrun/algos/ppo/ppo.hpp"
#include "rlrun/algos/sac/sac.hpp"
#include "rlrun/algos/td3/td3.hpp"
#include "rlrun/core/errors.hpp"

using namespace rlrun;

namespace {

template <class C>
C parse(const std::string& yaml) {
  return read_config<C>(ConfigNode::load_string(yaml, "exp.yaml"));
}

template <class C>
std::string error_of(const std::string& yaml) {
  try {
    parse<C>(yaml);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

// The resolved config's text of one key (flow style), e.g. "{pi: [32], vf: [64, 64]}".
template <class C>
std::string resolved(const C& config, const std::string& section, const std::string& key) {
  YAML::Emitter out;
  out.SetMapFormat(YAML::Flow);
  out.SetSeqFormat(YAML::Flow);
  out << write_config(config)[section][key];
  return out.c_str();
}

using Shape = std::vector<int64_t>;

}  // namespace

TEST_CASE("net_arch: a list means the same sizes for each network", "[algos][policy_options]") {
  const PPO::Config ppo = parse<PPO::Config>("policy: {net_arch: [32, 16]}");
  CHECK(ppo.policy.net_arch.pi == std::vector<int>{32, 16});
  CHECK(ppo.policy.net_arch.vf == std::vector<int>{32, 16});
  CHECK(resolved(ppo, "policy", "net_arch") == "[32, 16]");
  const SAC::Config sac = parse<SAC::Config>("policy: {net_arch: [64]}");
  CHECK(sac.policy.net_arch.pi == std::vector<int>{64});
  CHECK(sac.policy.net_arch.qf == std::vector<int>{64});
  // Defaults: SB3's (PPO/A2C [64, 64], SAC [256, 256], TD3/DDPG [400, 300]).
  CHECK(A2C::Config{}.policy.net_arch.vf == std::vector<int>{64, 64});
  CHECK(SAC::Config{}.policy.net_arch.qf == std::vector<int>{256, 256});
  CHECK(DDPG::Config{}.policy.net_arch.pi == std::vector<int>{400, 300});
}

TEST_CASE("net_arch: a {pi, vf} map for PPO/A2C, a {pi, qf} map for SAC/TD3/DDPG",
          "[algos][policy_options]") {
  const PPO::Config ppo = parse<PPO::Config>("policy: {net_arch: {pi: [32], vf: [64, 64]}}");
  CHECK(ppo.policy.net_arch.pi == std::vector<int>{32});
  CHECK(ppo.policy.net_arch.vf == std::vector<int>{64, 64});
  // Written back as a map, and read back to the same value (a model's config.yaml).
  CHECK(resolved(ppo, "policy", "net_arch") == "{pi: [32], vf: [64, 64]}");
  const PPO::Config again =
      read_config<PPO::Config>(ConfigNode::from_yaml(write_config(ppo), "model.zip:config.yaml"));
  CHECK(again.policy.net_arch == ppo.policy.net_arch);

  // Equal lists written as the list form.
  CHECK(resolved(parse<A2C::Config>("policy: {net_arch: {pi: [8], vf: [8]}}"), "policy",
                 "net_arch") == "[8]");

  // SB3's MlpExtractor: a key left out, or [], is no hidden layer (a linear head).
  const A2C::Config a2c = parse<A2C::Config>("policy: {net_arch: {vf: [16]}}");
  CHECK(a2c.policy.net_arch.pi.empty());
  CHECK(a2c.policy.net_arch.vf == std::vector<int>{16});
  CHECK(resolved(a2c, "policy", "net_arch") == "{pi: [], vf: [16]}");

  const SAC::Config sac = parse<SAC::Config>("policy: {net_arch: {pi: [64], qf: [400, 300]}}");
  CHECK(sac.policy.net_arch.pi == std::vector<int>{64});
  CHECK(sac.policy.net_arch.qf == std::vector<int>{400, 300});
  CHECK(resolved(sac, "policy", "net_arch") == "{pi: [64], qf: [400, 300]}");
  const TD3::Config td3 = parse<TD3::Config>("policy: {net_arch: {pi: [], qf: [32]}}");
  CHECK(td3.policy.net_arch.pi.empty());
  CHECK(td3.policy.net_arch.qf == std::vector<int>{32});
  CHECK(parse<DDPG::Config>("policy: {net_arch: {qf: [8], pi: [4]}}").policy.net_arch.qf ==
        std::vector<int>{8});
}

TEST_CASE("net_arch: wrong keys, missing keys and bad sizes are config errors",
          "[algos][policy_options]") {
  // A `qf` in a PPO entry (SB3 would ignore it silently) and a typo: did-you-mean, position.
  const std::string qf = error_of<PPO::Config>("policy:\n  net_arch: {pi: [8], qf: [8]}\n");
  CHECK_THAT(qf, Catch::Contains("exp.yaml:2:23: policy.net_arch.qf: unknown key 'qf' "
                                 "(did you mean 'vf'?)"));
  CHECK_THAT(qf, Catch::Contains("valid keys: pi, vf"));
  CHECK_THAT(error_of<PPO::Config>("policy: {net_arch: {pi: [8], vff: [8]}}"),
             Catch::Contains("unknown key 'vff' (did you mean 'vf'?)"));
  CHECK_THAT(error_of<SAC::Config>("policy: {net_arch: {pi: [8], vf: [8]}}"),
             Catch::Contains("unknown key 'vf' (did you mean 'qf'?)"));
  // SB3's get_actor_critic_arch asserts both keys.
  CHECK_THAT(error_of<TD3::Config>("policy: {net_arch: {pi: [8]}}"),
             Catch::Contains("needs both pi and qf (SB3's "
                             "get_actor_critic_arch); 'qf' is missing"));
  CHECK_THAT(error_of<PPO::Config>("policy: {net_arch: 64}"),
             Catch::Contains("expected a list [64, 64] (the same sizes for "
                             "each network) or a map"));
  CHECK_THAT(error_of<PPO::Config>("policy: {net_arch: {pi: 64}}"),
             Catch::Contains("policy.net_arch.pi: expected a list of layer sizes"));
  CHECK_THAT(error_of<SAC::Config>("policy: {net_arch: {pi: [8], qf: [8, 0]}}"),
             Catch::Contains("policy.net_arch.qf[1]: must be in [1, 65536], got 0"));
  CHECK_THAT(error_of<PPO::Config>("policy: {net_arch: [8, 100000]}"),
             Catch::Contains("policy.net_arch[1]: must be in [1, 65536], got 100000"));
  // DQN's QNetwork has one network: a list only.
  CHECK_THAT(error_of<DQN::Config>("policy: {net_arch: {pi: [8], qf: [8]}}"),
             Catch::Contains("expected a list"));
}

TEST_CASE("activation_fn: names and torch's classes for every algorithm",
          "[algos][policy_options]") {
  const PPO::Config ppo = parse<PPO::Config>("policy: {activation_fn: nn.ELU}");
  CHECK(ppo.policy.activation_fn == Activation::kELU);
  CHECK(resolved(ppo, "policy", "activation_fn") == "elu");  // the canonical name
  CHECK(parse<A2C::Config>("policy: {activation_fn: nn.ReLU}").policy.activation_fn ==
        Activation::kReLU);
  CHECK(parse<DQN::Config>("policy: {activation_fn: nn.Tanh}").policy.activation_fn ==
        Activation::kTanh);
  const SAC::Config sac = parse<SAC::Config>("policy: {activation_fn: nn.LeakyReLU}");
  CHECK(sac.policy.activation_fn == Activation::kLeakyReLU);
  CHECK(resolved(sac, "policy", "activation_fn") == "leaky_relu");
  CHECK(parse<TD3::Config>("policy: {activation_fn: elu}").policy.activation_fn ==
        Activation::kELU);
  CHECK(parse<DDPG::Config>("policy: {activation_fn: leaky_relu}").policy.activation_fn ==
        Activation::kLeakyReLU);
  const PPO::Config gelu = parse<PPO::Config>("policy: {activation_fn: nn.GELU}");  // CarRacing
  CHECK(gelu.policy.activation_fn == Activation::kGELU);
  CHECK(resolved(gelu, "policy", "activation_fn") == "gelu");
  CHECK(parse<DQN::Config>("policy: {activation_fn: gelu}").policy.activation_fn ==
        Activation::kGELU);
  CHECK(resolved(PPO::Config{}, "policy", "activation_fn") == "tanh");
  CHECK(resolved(SAC::Config{}, "policy", "activation_fn") == "relu");

  const std::string typo = error_of<DQN::Config>("policy:\n  activation_fn: nn.Relu\n");
  CHECK_THAT(typo, Catch::Contains("exp.yaml:2:18: policy.activation_fn: unknown activation "
                                   "'nn.Relu' (did you mean 'nn.ReLU'?)"));
  CHECK_THAT(typo, Catch::Contains("valid: tanh, relu, elu, leaky_relu, gelu (or torch's "
                                   "nn.Tanh, nn.ReLU, nn.ELU, nn.LeakyReLU, nn.GELU)"));
  CHECK_THAT(error_of<SAC::Config>("policy: {activation_fn: silu}"),
             Catch::Contains("unknown activation 'silu'"));
}

TEST_CASE("ActorCriticPolicy: separate pi / vf towers under SB3's state_dict names",
          "[algos][policy_options]") {
  ActorCriticPolicyConfig cfg;
  cfg.net_arch = {{32}, {64, 48}};
  Rng rng(1);
  ActorCriticPolicy policy(Space::box(-1.0f, 1.0f, {3}), Space::box(-2.0f, 2.0f, {2}), cfg, rng);
  CHECK(policy.actor().hidden() == std::vector<int>{32});
  CHECK(policy.critic().hidden() == std::vector<int>{64, 48});
  TensorMap t;
  policy.save(t);
  CHECK(t.at("mlp_extractor.policy_net.0.weight").shape == Shape{32, 3});
  CHECK(t.count("mlp_extractor.policy_net.2.weight") == 0);
  CHECK(t.at("action_net.weight").shape == Shape{2, 32});
  CHECK(t.at("mlp_extractor.value_net.0.weight").shape == Shape{64, 3});
  CHECK(t.at("mlp_extractor.value_net.2.weight").shape == Shape{48, 64});
  CHECK(t.at("value_net.weight").shape == Shape{1, 48});

  // pi: [] is a linear policy: action_net reads the features (no policy_net parameters).
  cfg.net_arch = {{}, {8}};
  ActorCriticPolicy linear(Space::box(-1.0f, 1.0f, {3}), Space::discrete(4), cfg, rng);
  TensorMap l;
  linear.save(l);
  CHECK(l.at("action_net.weight").shape == Shape{4, 3});
  for (const auto& [name, tensor] : l) CHECK(name.rfind("mlp_extractor.policy_net", 0) != 0);
  ActorCriticPolicy reloaded(Space::box(-1.0f, 1.0f, {3}), Space::discrete(4), cfg, rng);
  reloaded.load(l);
  CHECK(reloaded.actor().params() == linear.actor().params());
}

TEST_CASE(
    "ortho_init false: torch's default Linear init everywhere, log_std = "
    "log_std_init",
    "[algos][policy_options]") {
  ActorCriticPolicyConfig cfg;
  cfg.net_arch = {{64, 64}, {64, 64}};
  cfg.ortho_init = false;
  cfg.log_std_init = -2.0;
  Rng rng(4);
  ActorCriticPolicy policy(Space::box(-1.0f, 1.0f, {16}), Space::box(-1.0f, 1.0f, {3}), cfg, rng);
  // SB3 _build skips init_weights: every layer, action_net and value_net included, keeps
  // nn.Linear.reset_parameters: weight and bias U(-1/sqrt(fan_in), 1/sqrt(fan_in)).
  for (const Mlp* net : {&policy.actor(), &policy.critic()}) {
    for (int l = 0; l < net->num_layers(); ++l) {
      const double bound = 1.0 / std::sqrt(static_cast<double>(net->layer_in(l)));
      INFO("layer " << l << " of " << net->num_layers());
      CHECK(net->weight(l).cwiseAbs().maxCoeff() <= bound);
      CHECK(net->bias(l).cwiseAbs().maxCoeff() <= bound);
      CHECK_FALSE(net->bias(l).isZero());  // orthogonal init zeroes the biases
      // Uniform variance bound^2 / 3, far from the orthogonal action_net's (0.01^2 / fan_in).
      const double var = net->weight(l).array().square().mean();
      CHECK(var == Approx(bound * bound / 3.0).epsilon(0.25));
    }
  }
  TensorMap t;
  policy.save(t);
  Eigen::VectorXf log_std(3);
  from_tensor(t, "log_std", log_std);
  CHECK((log_std.array() == -2.0f).all());

  // The default (ortho_init true) still zeroes biases.
  cfg.ortho_init = true;
  ActorCriticPolicy ortho(Space::box(-1.0f, 1.0f, {16}), Space::box(-1.0f, 1.0f, {3}), cfg, rng);
  CHECK(ortho.actor().bias(0).isZero());
}

TEST_CASE("SAC, TD3, DDPG: the actor takes net_arch.pi, each critic net_arch.qf",
          "[algos][policy_options]") {
  const AlgorithmSetup setup{Space::box(-1.0f, 1.0f, {3}), Space::box(-2.0f, 2.0f, {1}), 1, 5};
  const auto shapes_of = [](const Algorithm& algo) {
    TensorMap t;
    algo.save(t);
    return t;
  };
  SAC::Config sac;
  sac.policy.net_arch = {{64}, {400, 300}};
  sac.policy.activation_fn = Activation::kLeakyReLU;
  const TensorMap s = shapes_of(SAC(sac, setup));
  CHECK(s.at("actor.latent_pi.0.weight").shape == Shape{64, 3});
  CHECK(s.count("actor.latent_pi.2.weight") == 0);
  CHECK(s.at("actor.mu.weight").shape == Shape{1, 64});
  CHECK(s.at("actor.log_std.weight").shape == Shape{1, 64});
  CHECK(s.at("critic.qf0.0.weight").shape == Shape{400, 4});
  CHECK(s.at("critic.qf1.2.weight").shape == Shape{300, 400});
  CHECK(s.at("critic.qf1.4.weight").shape == Shape{1, 300});
  CHECK(s.at("critic_target.qf0.4.weight").shape == Shape{1, 300});

  // pi: [] — SB3's Actor with an empty latent_pi: mu and log_std read the features.
  sac.policy.net_arch = {{}, {16}};
  const TensorMap linear = shapes_of(SAC(sac, setup));
  CHECK(linear.at("actor.mu.weight").shape == Shape{1, 3});
  CHECK(linear.count("actor.latent_pi.0.weight") == 0);

  TD3::Config td3;
  td3.policy.net_arch = {{16}, {32, 8}};
  const TensorMap t = shapes_of(TD3(td3, setup));
  CHECK(t.at("actor.mu.0.weight").shape == Shape{16, 3});
  CHECK(t.at("actor.mu.2.weight").shape == Shape{1, 16});
  CHECK(t.at("actor_target.mu.2.weight").shape == Shape{1, 16});
  CHECK(t.at("critic.qf1.2.weight").shape == Shape{8, 32});

  DDPG::Config ddpg;
  ddpg.policy.net_arch = {{4}, {12}};
  ddpg.policy.activation_fn = Activation::kELU;
  const TensorMap d = shapes_of(DDPG(ddpg, setup));
  CHECK(d.at("actor.mu.0.weight").shape == Shape{4, 3});
  CHECK(d.at("critic.qf0.0.weight").shape == Shape{12, 4});
  CHECK(d.count("critic.qf1.0.weight") == 0);
}

namespace {

// Builds an algorithm from `yaml`, saves it, rebuilds it from its resolved config (as a model
// file's config.yaml is read back) with another seed, loads the tensors: same actions.
template <class A>
void check_save_load_same_actions(const std::string& yaml, const AlgorithmSetup& setup) {
  const typename A::Config config = parse<typename A::Config>(yaml);
  A original(config, setup);
  TensorMap tensors;
  original.save(tensors);
  const typename A::Config reread = read_config<typename A::Config>(
      ConfigNode::from_yaml(write_config(config), "model.zip:config.yaml"));
  AlgorithmSetup other = setup;
  other.seed = setup.seed + 100;  // different initial weights, overwritten by load
  A reloaded(reread, other);
  reloaded.load(tensors);
  Rng rng(9);
  Eigen::MatrixXf obs(setup.observation_space.flat_dim(), 16);
  for (Eigen::Index k = 0; k < obs.size(); ++k) obs(k) = static_cast<float>(rng.normal());
  Eigen::MatrixXf a, b;
  original.predict(obs, true, a);
  reloaded.predict(obs, true, b);
  CHECK(a == b);
  A fresh(reread, other);
  fresh.predict(obs, true, b);
  CHECK(a != b);  // the load, not the seed, made them equal
}

}  // namespace

TEST_CASE("save -> load -> same actions with the new network options", "[algos][policy_options]") {
  const AlgorithmSetup setup{Space::box(-1.0f, 1.0f, {3}), Space::box(-2.0f, 2.0f, {2}), 1, 5};
  check_save_load_same_actions<PPO>(
      "policy: {net_arch: {pi: [32], vf: [64, 64]}, activation_fn: nn.ELU, "
      "ortho_init: false}",
      setup);
  check_save_load_same_actions<A2C>("policy: {net_arch: {pi: [], vf: [8]}, activation_fn: relu}",
                                    setup);
  check_save_load_same_actions<SAC>(
      "policy: {net_arch: {pi: [64], qf: [400, "
      "300]}, activation_fn: nn.LeakyReLU}",
      setup);
  check_save_load_same_actions<TD3>("policy: {net_arch: {pi: [16], qf: [8]}, activation_fn: elu}",
                                    setup);
  check_save_load_same_actions<DDPG>("policy: {net_arch: [12], activation_fn: nn.Tanh}", setup);
  check_save_load_same_actions<DQN>("policy: {net_arch: [], activation_fn: nn.LeakyReLU}",
                                    {Space::box(-1.0f, 1.0f, {3}), Space::discrete(4), 1, 5});
}

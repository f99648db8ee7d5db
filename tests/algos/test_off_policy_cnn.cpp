// SB3's CnnPolicy for SAC, TQC, TD3 and DDPG (sac/policies.py, td3/policies.py, sb3-contrib
// tqc/policies.py with share_features_extractor=False): the actor and the critic each read a
// NatureCNN of their own, the critic's learns from the critic loss of every Q-network, the
// actor's from the actor loss, and the targets' CNNs are copies moved by Polyak averaging.
// The gradients are checked against central differences of a double re-implementation
// (nn/nature_cnn_reference.hpp, test::mlp_forward) that reads the networks' parameters.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <functional>
#include <limits>
#include <string>

#include "algos/entropy_regularized_fixtures.hpp"
#include "nn/grad_check.hpp"
#include "nn/nature_cnn_gradient_check.hpp"
#include "nn/nature_cnn_reference.hpp"
#include "rlrun/algos/sac/sac.hpp"
#include "rlrun/algos/td3/td3.hpp"
#include "rlrun/algos/tqc/tqc.hpp"
#include "rlrun/nn/policy_graph.hpp"

using namespace rlrun;

namespace {

constexpr int kSide = 36;  // the smallest image NatureCNN takes
constexpr int kActDim = 2;
constexpr int kFeatures = 8;

AlgorithmSetup image_setup(uint64_t seed = 11) {
  return AlgorithmSetup{Space::image({kSide, kSide, 1}),
                        Space::box({-1.0f, 0.0f}, {1.0f, 2.0f}, {kActDim}), 1, seed};
}

// Whole-number pixels 0-255, actions in (-1, 1), every third transition terminal.
ReplayBatch image_batch(int n, uint64_t seed) {
  Rng rng(seed);
  ReplayBatch b;
  b.obs.resize(kSide * kSide, n);
  b.next_obs.resize(kSide * kSide, n);
  for (Eigen::Index k = 0; k < b.obs.size(); ++k) {
    b.obs(k) = static_cast<float>(std::floor(rng.uniform(0.0, 256.0)));
    b.next_obs(k) = static_cast<float>(std::floor(rng.uniform(0.0, 256.0)));
  }
  b.actions = test::random_matrix(rng, kActDim, n, 0.5).cwiseMax(-0.99f).cwiseMin(0.99f);
  b.rewards = test::random_matrix(rng, 1, n);
  b.dones = Eigen::RowVectorXf::Zero(n);
  for (int j = 0; j < n; j += 3) b.dones(j) = 1.0f;
  return b;
}

// Q_i(o, a) in double through critic i and the critic's CNN `cnn`.
double q_value(const ContinuousCritic& critic, int i, const NatureCnn& cnn,
               const Eigen::VectorXf& obs, const Eigen::VectorXd& action, int output = 0) {
  const Mlp& q = critic.q(i).net();
  return test::mlp_forward_one(q, test::params_of(q),
                               test::concat(test::reference_features(cnn, obs), action))(output);
}

// Central differences over ~41 parameters of every layer of `net`, against its grads().
void check_cnn_gradient(const NatureCnn& net, const std::function<double(const NatureCnn&)>& loss,
                        const std::string& what) {
  CHECK(test::check_cnn_gradient(net, loss, what, 41, 1e-5, 1e-2) > 40);
}

template <class Config>
void use_cnn(Config& policy) {
  policy.features_extractor_class = FeaturesExtractor::kNatureCnn;
  policy.features_dim = kFeatures;
  policy.net_arch = {{16}, {16}};
}

SAC::Config sac_cnn_config() {
  SAC::Config c;
  use_cnn(c.policy);
  c.off_policy.batch_size = 6;
  return c;
}

TD3::Config td3_cnn_config() {
  TD3::Config c;
  use_cnn(c.policy);
  c.off_policy.batch_size = 6;
  return c;
}

}  // namespace

TEST_CASE("SAC CnnPolicy: actor and critic each learn their own NatureCNN from their own loss",
          "[algos][sac][cnn][gradcheck]") {
  SAC sac(sac_cnn_config(), image_setup());
  const NatureCnn& actor_cnn = sac.actor().features_extractor().cnn();
  const NatureCnn& critic_cnn = sac.critic().features_extractor().cnn();
  const NatureCnn& target_cnn = sac.critic_target().features_extractor().cnn();
  REQUIRE(sac.actor().features_extractor().learned());
  CHECK(actor_cnn.params() != critic_cnn.params());   // two extractors, drawn apart
  CHECK(target_cnn.params() == critic_cnn.params());  // critic_target.load_state_dict(critic)
  CHECK(sac.actor().net().in_dim() == kFeatures);
  CHECK(sac.critic().q(0).net().in_dim() == kFeatures + kActDim);

  const int n = 5;
  const ReplayBatch b = image_batch(n, 3);
  // Learning rate 0: the parameters stay, the gradients stay in grads().
  const EntropyRegularizedStepStats stats = sac.train_on_batch(b, 0.0f, false);
  const double alpha = stats.ent_coef, gamma = 0.99;

  // The soft target through the actor's CNN on s' and the target critic's CNN.
  for (int j = 0; j < n; ++j) {
    const Eigen::VectorXd f = test::reference_features(actor_cnn, b.next_obs.col(j));
    const auto [a, lp] =
        test::actor_sample(sac.actor().net(), test::params_of(sac.actor().net()), kActDim, f,
                           sac.last_next_noise().col(j).cast<double>());
    double min_q = std::numeric_limits<double>::infinity();
    for (int i = 0; i < 2; ++i)
      min_q = std::min(min_q, q_value(sac.critic_target(), i, target_cnn, b.next_obs.col(j), a));
    const double y = b.rewards(j) + (1.0 - b.dones(j)) * gamma * (min_q - alpha * lp);
    CHECK(sac.last_critic_target()(0, j) == Approx(y).epsilon(1e-4).margin(1e-5));
  }

  // critic_loss = 0.5 sum_i mean_j (Q_i(s_j, a_j) - y_j)^2: its gradient in the critic's CNN
  // sums both Q-networks' (SB3's one critic optimizer over critic.parameters()).
  auto critic_loss = [&](const NatureCnn& cnn) {
    double loss = 0.0;
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < n; ++j) {
        const double d =
            q_value(sac.critic(), i, cnn, b.obs.col(j), b.actions.col(j).cast<double>()) -
            sac.last_critic_target()(0, j);
        loss += 0.5 * d * d / n;
      }
    return loss;
  };
  CHECK(stats.critic_loss == Approx(critic_loss(critic_cnn)).epsilon(1e-4));
  check_cnn_gradient(critic_cnn, critic_loss, "critic CNN");

  // actor_loss = mean_j(alpha log pi(a_j|s_j) - min_i Q_i(s_j, a_j)): the actor's CNN learns
  // through the sample and its log-probability; the critic's CNN reads s_j.
  auto actor_loss = [&](const NatureCnn& cnn) {
    double loss = 0.0;
    for (int j = 0; j < n; ++j) {
      const Eigen::VectorXd f = test::reference_features(cnn, b.obs.col(j));
      const auto [a, lp] =
          test::actor_sample(sac.actor().net(), test::params_of(sac.actor().net()), kActDim, f,
                             sac.last_policy_noise().col(j).cast<double>());
      const double q = std::min(q_value(sac.critic(), 0, critic_cnn, b.obs.col(j), a),
                                q_value(sac.critic(), 1, critic_cnn, b.obs.col(j), a));
      loss += (alpha * lp - q) / n;
    }
    return loss;
  };
  CHECK(stats.actor_loss == Approx(actor_loss(actor_cnn)).epsilon(1e-4));
  check_cnn_gradient(actor_cnn, actor_loss, "actor CNN");
}

TEST_CASE("SAC CnnPolicy: the target CNN follows by Polyak, the acting copy by each step",
          "[algos][sac][cnn]") {
  SAC::Config config = sac_cnn_config();
  config.off_policy.tau = 0.25;
  SAC sac(config, image_setup());
  const ReplayBatch b = image_batch(6, 4);
  const Eigen::VectorXf actor0 = sac.actor().features_extractor().cnn().params();
  const Eigen::VectorXf target0 = sac.critic_target().features_extractor().cnn().params();
  sac.train_on_batch(b, 1e-3f, true);
  const Eigen::VectorXf& critic1 = sac.critic().features_extractor().cnn().params();
  CHECK(sac.actor().features_extractor().cnn().params() != actor0);
  CHECK(critic1 != target0);
  const Eigen::VectorXf expected = 0.75f * target0 + 0.25f * critic1;
  CHECK((sac.critic_target().features_extractor().cnn().params() - expected).cwiseAbs().maxCoeff() <
        1e-6f);
  // predict() acts with the trained CNN: the same action as a fresh model loaded from it.
  TensorMap tensors;
  sac.save(tensors);
  SAC loaded(config, image_setup(99));
  loaded.load(tensors);
  Eigen::MatrixXf a, a_loaded;
  sac.predict(b.obs, true, a);
  loaded.predict(b.obs, true, a_loaded);
  CHECK(a == a_loaded);
}

TEST_CASE("SAC, TQC and TD3 CnnPolicy save SB3's names for every extractor",
          "[algos][sac][td3][tqc][cnn]") {
  TensorMap sac_tensors, tqc_tensors, td3_tensors;
  SAC(sac_cnn_config(), image_setup()).save(sac_tensors);
  TQC::Config tqc_config;
  use_cnn(tqc_config.policy);
  TQC(tqc_config, image_setup()).save(tqc_tensors);
  TD3(td3_cnn_config(), image_setup()).save(td3_tensors);
  for (const std::string module : {"actor", "critic", "critic_target"}) {
    INFO(module);
    for (const TensorMap* t : {&sac_tensors, &tqc_tensors, &td3_tensors}) {
      CHECK(t->count(module + ".features_extractor.cnn.0.weight") == 1);
      CHECK(t->count(module + ".features_extractor.cnn.4.bias") == 1);
      CHECK(t->at(module + ".features_extractor.linear.0.weight").shape ==
            std::vector<int64_t>{kFeatures, 64});
    }
  }
  CHECK(td3_tensors.count("actor_target.features_extractor.cnn.2.weight") == 1);
  CHECK(sac_tensors.count("features_extractor.cnn.0.weight") == 0);
}

TEST_CASE("SAC and TD3 CnnPolicy export as graphs that act as predict() does",
          "[algos][sac][td3][cnn][deploy]") {
  const ReplayBatch b = image_batch(7, 12);
  auto check = [&](Algorithm& algo) {
    PolicyGraph graph;
    graph.add_input("obs", kSide * kSide);
    algo.export_policy(graph, "obs", /*with_value=*/true);
    const auto values = evaluate_graph(graph, {b.obs});
    Eigen::MatrixXf expected;
    algo.predict(b.obs, true, expected);
    const Eigen::MatrixXf& got = values.at(graph.action());
    REQUIRE(got.rows() == expected.rows());
    CHECK((got - expected).cwiseAbs().maxCoeff() < 1e-5f);
  };
  SAC sac(sac_cnn_config(), image_setup());
  sac.train_on_batch(b, 1e-2f, true);  // actor and critic CNNs apart from their start
  check(sac);
  TD3::Config td3_config = td3_cnn_config();
  td3_config.policy_delay = 1;
  TD3 td3(td3_config, image_setup());
  td3.train_on_batch(b, 1e-2f);
  check(td3);
}

TEST_CASE("TD3 CnnPolicy: critic CNN from the critic loss, actor CNN on delayed steps",
          "[algos][td3][cnn][gradcheck]") {
  TD3 td3(td3_cnn_config(), image_setup());
  const NatureCnn& actor_cnn = td3.actor().features_extractor().cnn();
  const NatureCnn& critic_cnn = td3.critic().features_extractor().cnn();
  CHECK(td3.actor_target().features_extractor().cnn().params() == actor_cnn.params());
  CHECK(actor_cnn.params() != critic_cnn.params());
  const int n = 5;
  const ReplayBatch b = image_batch(n, 8);

  // Step 1 (policy_delay 2): the critics and their CNN only.
  const Td3StepStats first = td3.train_on_batch(b, 0.0f);
  REQUIRE_FALSE(first.actor_updated);
  auto critic_loss = [&](const NatureCnn& cnn) {
    double loss = 0.0;
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < n; ++j) {
        const double d =
            q_value(td3.critic(), i, cnn, b.obs.col(j), b.actions.col(j).cast<double>()) -
            td3.last_critic_target()(0, j);
        loss += d * d / n;
      }
    return loss;
  };
  CHECK(first.critic_loss == Approx(critic_loss(critic_cnn)).epsilon(1e-4));
  check_cnn_gradient(critic_cnn, critic_loss, "critic CNN");

  // Step 2: actor_loss = -mean_j Q_1(s_j, tanh(mu(features(s_j)))), the critic's features
  // without gradient (q1_forward).
  const Td3StepStats second = td3.train_on_batch(b, 0.0f);
  REQUIRE(second.actor_updated);
  auto actor_loss = [&](const NatureCnn& cnn) {
    double loss = 0.0;
    for (int j = 0; j < n; ++j) {
      const Eigen::VectorXd f = test::reference_features(cnn, b.obs.col(j));
      const Eigen::VectorXd a =
          test::mlp_forward_one(td3.actor().net(), test::params_of(td3.actor().net()), f)
              .array()
              .tanh()
              .matrix();
      loss -= q_value(td3.critic(), 0, critic_cnn, b.obs.col(j), a) / n;
    }
    return loss;
  };
  CHECK(second.actor_loss == Approx(actor_loss(actor_cnn)).epsilon(1e-4));
  check_cnn_gradient(actor_cnn, actor_loss, "actor CNN");
}

TEST_CASE("TD3 CnnPolicy: the actor's and the critic's target CNNs move by Polyak",
          "[algos][td3][cnn]") {
  TD3::Config config = td3_cnn_config();
  config.policy_delay = 1;
  config.off_policy.tau = 0.5;
  TD3 td3(config, image_setup());
  const Eigen::VectorXf actor_target0 = td3.actor_target().features_extractor().cnn().params();
  const Eigen::VectorXf critic_target0 = td3.critic_target().features_extractor().cnn().params();
  td3.train_on_batch(image_batch(6, 9), 1e-3f);
  const Eigen::VectorXf& actor1 = td3.actor().features_extractor().cnn().params();
  const Eigen::VectorXf& critic1 = td3.critic().features_extractor().cnn().params();
  CHECK(actor1 != actor_target0);
  CHECK(critic1 != critic_target0);
  CHECK((td3.actor_target().features_extractor().cnn().params() -
         (0.5f * actor_target0 + 0.5f * actor1))
            .cwiseAbs()
            .maxCoeff() < 1e-6f);
  CHECK((td3.critic_target().features_extractor().cnn().params() -
         (0.5f * critic_target0 + 0.5f * critic1))
            .cwiseAbs()
            .maxCoeff() < 1e-6f);
}

TEST_CASE(
    "Off-policy CnnPolicy: SB3's image rules and the unsupported sharing are refused at "
    "their keys",
    "[algos][cnn][config]") {
  SAC::Config sac = sac_cnn_config();
  // A vector observation is no image: SB3's NatureCNN assertion, at the key.
  const AlgorithmSetup vector_obs{Space::box(-1.0f, 1.0f, {3}), image_setup().action_space, 1, 1};
  ConfigProblems p = SAC::check(sac, vector_obs);
  REQUIRE_FALSE(p.empty());
  CHECK(p.front().key == "policy.features_extractor_class");
  CHECK_THAT(p.front().message, Catch::Contains("NatureCNN only with images"));
  // Float pixels are not an image space (SB3 asks for uint8).
  const AlgorithmSetup float_image{Space::box(0.0f, 255.0f, {kSide, kSide, 1}),
                                   image_setup().action_space, 1, 1};
  p = TD3::check(td3_cnn_config(), float_image);
  REQUIRE_FALSE(p.empty());
  CHECK_THAT(p.front().message, Catch::Contains("uint8"));
  sac.policy.share_features_extractor = true;
  CHECK(SAC::check(sac, image_setup()).empty());
  CHECK(SAC::check(sac_cnn_config(), image_setup()).empty());
}

TEST_CASE(
    "SAC share_features_extractor: the critic reads the actor's CNN, which only the actor "
    "loss trains, and the target keeps a copy moved by Polyak",
    "[algos][sac][cnn][gradcheck]") {
  SAC::Config config = sac_cnn_config();
  config.policy.share_features_extractor = true;
  SAC sac(config, image_setup());
  const NatureCnn& cnn = sac.actor().features_extractor().cnn();
  CHECK(&sac.critic().features_extractor() == &sac.actor().features_extractor());
  CHECK(&sac.critic_target().features_extractor() != &sac.actor().features_extractor());
  CHECK(sac.critic_target().features_extractor().cnn().params() == cnn.params());

  const int n = 5;
  const ReplayBatch b = image_batch(n, 13);
  const EntropyRegularizedStepStats stats = sac.train_on_batch(b, 0.0f, false);
  const double alpha = stats.ent_coef;
  // The actor loss's gradient with the critic's features held fixed (SB3 computes them under
  // th.set_grad_enabled(False)): the critic reads the unperturbed CNN.
  const NatureCnn fixed = cnn;
  auto actor_loss = [&](const NatureCnn& perturbed) {
    double loss = 0.0;
    for (int j = 0; j < n; ++j) {
      const Eigen::VectorXd f = test::reference_features(perturbed, b.obs.col(j));
      const auto [a, lp] =
          test::actor_sample(sac.actor().net(), test::params_of(sac.actor().net()), kActDim, f,
                             sac.last_policy_noise().col(j).cast<double>());
      const double q = std::min(q_value(sac.critic(), 0, fixed, b.obs.col(j), a),
                                q_value(sac.critic(), 1, fixed, b.obs.col(j), a));
      loss += (alpha * lp - q) / n;
    }
    return loss;
  };
  check_cnn_gradient(cnn, actor_loss, "shared CNN");

  // SB3's state dict lists the shared CNN under critic too; the target's is its own.
  TensorMap tensors;
  sac.save(tensors);
  CHECK(tensors.count("critic.features_extractor.cnn.0.weight") == 1);
  // Polyak: the target's CNN moves towards the actor's (critic.parameters() holds it).
  config.off_policy.tau = 0.5;
  SAC moving(config, image_setup());
  const Eigen::VectorXf target0 = moving.critic_target().features_extractor().cnn().params();
  moving.train_on_batch(b, 1e-2f, true);
  const Eigen::VectorXf& actor1 = moving.actor().features_extractor().cnn().params();
  CHECK(actor1 != target0);
  CHECK((moving.critic_target().features_extractor().cnn().params() -
         (0.5f * target0 + 0.5f * actor1))
            .cwiseAbs()
            .maxCoeff() < 1e-6f);
}

TEST_CASE(
    "TD3 share_features_extractor: the critic target reads the actor target's CNN, moved "
    "by both Polyak updates (SB3's 2 tau)",
    "[algos][td3][cnn]") {
  TD3::Config config = td3_cnn_config();
  config.policy.share_features_extractor = true;
  config.policy_delay = 1;
  config.off_policy.tau = 0.25;
  TD3 td3(config, image_setup());
  CHECK(&td3.critic().features_extractor() == &td3.actor().features_extractor());
  CHECK(&td3.critic_target().features_extractor() == &td3.actor_target().features_extractor());
  const Eigen::VectorXf target0 = td3.actor_target().features_extractor().cnn().params();
  td3.train_on_batch(image_batch(6, 14), 1e-2f);
  const Eigen::VectorXf& actor1 = td3.actor().features_extractor().cnn().params();
  const Eigen::VectorXf once = 0.75f * target0 + 0.25f * actor1;
  const Eigen::VectorXf twice = 0.75f * once + 0.25f * actor1;
  CHECK((td3.actor_target().features_extractor().cnn().params() - twice).cwiseAbs().maxCoeff() <
        1e-6f);
}

// ActorCriticPolicy's NatureCNN with share_features_extractor false (SB3's
// pi_features_extractor and vf_features_extractor): the critic's loss reaches only the
// critic's CNN, its gradient matches central differences of a double re-implementation that
// reads the saved torch tensors, and the model holds SB3's names for both.
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "nn/grad_check.hpp"
#include "nn/nature_cnn_gradient_check.hpp"
#include "nn/nature_cnn_reference.hpp"
#include "rlrun/algos/common/actor_critic_policy.hpp"

using namespace rlrun;

TEST_CASE("ActorCriticPolicy: share_features_extractor false gives the critic its own NatureCNN",
          "[algos][cnn][gradcheck]") {
  ActorCriticPolicyConfig config;
  config.features_extractor_class = FeaturesExtractor::kNatureCnn;
  config.features_dim = 8;
  config.share_features_extractor = false;
  config.net_arch = {{}, {}};
  const Space image = Space::image({36, 36, 1});
  Rng init(3);
  ActorCriticPolicy policy(image, Space::discrete(3), config, init, false);
  REQUIRE(policy.cnn() != nullptr);
  REQUIRE(policy.value_cnn() != nullptr);
  // Two extractors, initialised apart (SB3 draws both).
  CHECK(policy.cnn()->params() != policy.value_cnn()->params());

  const int n = 4;
  Rng rng(5);
  Eigen::MatrixXf obs(36 * 36, n), actions(1, n);
  for (Eigen::Index k = 0; k < obs.size(); ++k)
    obs.data()[k] = static_cast<float>(std::floor(rng.uniform(0.0, 256.0)));
  for (int j = 0; j < n; ++j) actions(0, j) = static_cast<float>(j % 3);
  Eigen::RowVectorXf values, log_prob, entropy;
  policy.evaluate_actions(obs, actions, values, log_prob, entropy);
  // A value loss alone: sum_j g_j V(obs_j).
  Eigen::RowVectorXf grad_values(n), zeros = Eigen::RowVectorXf::Zero(n);
  for (int j = 0; j < n; ++j) grad_values(j) = static_cast<float>(rng.normal());
  policy.zero_grad();
  policy.backward(grad_values, zeros, zeros);
  CHECK(policy.cnn()->grads().isZero());  // the actor's CNN gets nothing of the value loss
  const NatureCnn vf = *policy.value_cnn();
  CHECK(vf.grads().norm() > 0.0f);
  const Eigen::VectorXd critic = policy.critic().params().cast<double>();
  auto value_loss = [&](const NatureCnn& net) {
    double sum = 0.0;
    for (int j = 0; j < n; ++j)
      sum += grad_values(j) * test::mlp_forward(policy.critic(), critic,
                                                test::reference_features(net, obs.col(j)))(0, 0);
    return sum;
  };
  for (int j = 0; j < n; ++j) {
    const double v =
        test::mlp_forward(policy.critic(), critic, test::reference_features(vf, obs.col(j)))(0, 0);
    CHECK(values(j) == Approx(v).epsilon(1e-4).margin(1e-5));
  }
  CHECK(test::check_cnn_gradient(vf, value_loss, "critic CNN", 53, 1e-5, 1e-2) > 50);

  // SB3's state_dict names; a reload gives the same networks.
  TensorMap tensors;
  policy.save(tensors);
  CHECK(tensors.count("pi_features_extractor.cnn.0.weight") == 1);
  CHECK(tensors.count("vf_features_extractor.linear.0.bias") == 1);
  CHECK(tensors.count("features_extractor.cnn.0.weight") == 0);
  Rng other(99);
  ActorCriticPolicy loaded(image, Space::discrete(3), config, other, false);
  loaded.load(tensors);
  CHECK(loaded.value_cnn()->params() == policy.value_cnn()->params());
  CHECK(loaded.cnn()->params() == policy.cnn()->params());
}

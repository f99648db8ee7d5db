// SB3's CombinedExtractor (MultiInputPolicy, common/torch_layers.py): on a Dict, each image key
// (a uint8 Box of three dimensions, 0-255) through a NatureCNN of cnn_output_dim features, every
// other key flattened, concatenated in the Dict's key order. Its features are checked against
// the double reference of each CNN, its gradient against central differences, its names
// against SB3's, and a PPO policy and a DQN on it against their exported graphs.
#include <catch2/catch.hpp>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "nn/nature_cnn_gradient_check.hpp"
#include "nn/nature_cnn_reference.hpp"
#include "rlrun/algos/common/actor_critic_policy.hpp"
#include "rlrun/algos/common/features_extractor_net.hpp"
#include "rlrun/algos/dqn/dqn.hpp"
#include "rlrun/env/observation_encoder.hpp"
#include "rlrun/nn/policy_graph.hpp"

using namespace rlrun;

namespace {

// Dict(camera: Box(0, 255, (36, 36, 1), uint8), state: Box(-1, 1, (3,)), step: Discrete(4)),
// keys in sorted order as Gymnasium's Dict keeps them.
Space camera_dict() {
  return Space::dict({{"camera", Space::image({36, 36, 1})},
                      {"state", Space::box(-1.0f, 1.0f, {3})},
                      {"step", Space::discrete(4)}});
}

Eigen::MatrixXf camera_observations(const Space& space, int n, uint64_t seed) {
  Rng rng(seed);
  Eigen::MatrixXf obs(space.flat_dim(), n);
  for (int j = 0; j < n; ++j)
    space.sample(rng, {obs.col(j).data(), static_cast<size_t>(obs.rows())});
  return obs;
}

FeaturesExtractorSettings combined(int cnn_output_dim = 8) {
  FeaturesExtractorSettings s;
  s.kind = FeaturesExtractor::kCombined;
  s.cnn_output_dim = cnn_output_dim;
  return s;
}

}  // namespace

TEST_CASE("CombinedExtractor: a NatureCNN per image key, the other keys flattened, in key order",
          "[algos][cnn][combined][gradcheck]") {
  const Space space = camera_dict();
  ObservationEncoder encoder(space);  // no /255: the CNNs divide their own input
  FeaturesExtractorNet net(combined(), space, encoder.features_dim(), nullptr);
  REQUIRE(net.num_cnns() == 1);
  CHECK(net.out_dim() == 8 + 3 + 4);  // camera's CNN, state, step's one-hot
  Rng init(2);
  net.init_torch_default(init);

  const int n = 4;
  const Eigen::MatrixXf obs = camera_observations(space, n, 6);
  Eigen::MatrixXf encoded;
  encoder.encode(obs, encoded);
  const Eigen::MatrixXf features = net.forward(encoded);
  for (int j = 0; j < n; ++j) {
    const Eigen::VectorXd cnn = test::reference_features(net.cnn(), encoded.col(j).head(36 * 36));
    for (int k = 0; k < 8; ++k) CHECK(features(k, j) == Approx(cnn(k)).epsilon(1e-4).margin(1e-5));
    CHECK(features.col(j).tail(7) == encoded.col(j).tail(7));
  }

  // A linear loss sum g . features: the CNN's gradient from its rows only.
  Rng rng(8);
  Eigen::MatrixXf g(net.out_dim(), n);
  for (Eigen::Index k = 0; k < g.size(); ++k) g(k) = static_cast<float>(rng.normal());
  net.zero_grad_and_backward(g);
  auto loss = [&](const NatureCnn& cnn) {
    double sum = 0.0;
    for (int j = 0; j < n; ++j)
      sum += g.col(j).head(8).cast<double>().dot(
          test::reference_features(cnn, encoded.col(j).head(36 * 36)));
    return sum;
  };
  CHECK(test::check_cnn_gradient(net.cnn(), loss, "camera CNN", 41, 1e-5, 1e-2) > 40);

  // SB3's names: features_extractor.extractors.<key>.cnn.0.weight ...
  TensorMap tensors;
  net.save("features_extractor", tensors);
  CHECK(tensors.count("features_extractor.extractors.camera.cnn.0.weight") == 1);
  CHECK(tensors.count("features_extractor.extractors.camera.linear.0.bias") == 1);
  CHECK(tensors.size() == 8);
  FeaturesExtractorNet loaded(combined(), space, encoder.features_dim(), nullptr);
  loaded.load("features_extractor", tensors);
  CHECK(loaded.cnn().params() == net.cnn().params());

  // Without an image key it is the flatten extractor (SB3: nn.Flatten per key), no parameters.
  const Space vectors =
      Space::dict({{"a", Space::box(-1.0f, 1.0f, {2})}, {"b", Space::discrete(3)}});
  const FeaturesExtractorNet flat(combined(), vectors, ObservationEncoder(vectors).features_dim(),
                                  nullptr);
  CHECK_FALSE(flat.learned());
  CHECK(flat.out_dim() == 5);
  // A non-Dict observation is refused with SB3's reason.
  CHECK_THROWS_WITH(FeaturesExtractorNet(combined(), Space::image({36, 36, 1}), 1296, nullptr),
                    Catch::Contains("reads Dict observations"));
}

TEST_CASE("CombinedExtractor in PPO and DQN: SB3's names, and exports that act as predict does",
          "[algos][cnn][combined][deploy]") {
  const Space space = camera_dict();
  const Eigen::MatrixXf obs = camera_observations(space, 6, 9);
  auto check_graph = [&](const std::function<void(PolicyGraph&, const std::string&)>& build,
                         const Eigen::MatrixXf& expected) {
    PolicyGraph graph;
    std::vector<std::string> keys;
    std::vector<Eigen::MatrixXf> inputs;
    Eigen::Index row = 0;
    for (size_t i = 0; i < space.keys().size(); ++i) {
      const int w = space.subspaces()[i].flat_dim();
      graph.add_input(space.keys()[i], w);
      keys.push_back(space.keys()[i]);
      inputs.push_back(obs.middleRows(row, w));
      row += w;
    }
    build(graph, graph.concat(keys));
    const auto values = evaluate_graph(graph, inputs);
    const Eigen::MatrixXf& got = values.at(graph.action());
    REQUIRE(got.cols() == expected.cols());
    CHECK((got - expected).cwiseAbs().maxCoeff() < 1e-5f);
  };

  ActorCriticPolicyConfig config;
  config.features_extractor_class = FeaturesExtractor::kCombined;
  config.cnn_output_dim = 8;
  config.net_arch = {{16}, {16}};
  Rng init(4);
  ActorCriticPolicy policy(space, Space::box(-1.0f, 1.0f, {2}), config, init);
  TensorMap tensors;
  policy.save(tensors);
  CHECK(tensors.count("features_extractor.extractors.camera.cnn.0.weight") == 1);
  CHECK(tensors.at("mlp_extractor.policy_net.0.weight").shape ==
        std::vector<int64_t>{16, 8 + 3 + 4});
  Eigen::MatrixXf actions;
  Eigen::RowVectorXf values, log_prob;
  Rng act_rng(1);
  policy.act(obs, act_rng, true, actions, values, log_prob);
  check_graph(
      [&](PolicyGraph& g, const std::string& in) {
        policy.export_to(g, in, Space::box(-1.0f, 1.0f, {2}), false);
      },
      actions);

  DQN::Config dqn_config;
  dqn_config.policy.features_extractor_class = FeaturesExtractor::kCombined;
  dqn_config.policy.cnn_output_dim = 8;
  dqn_config.policy.net_arch = {};
  DQN dqn(dqn_config, AlgorithmSetup{space, Space::discrete(3), 1, 5});
  TensorMap q_tensors;
  dqn.save(q_tensors);
  CHECK(q_tensors.count("q_net.features_extractor.extractors.camera.cnn.2.weight") == 1);
  CHECK(q_tensors.count("q_net_target.features_extractor.extractors.camera.linear.0.weight") == 1);
  Eigen::MatrixXf greedy;
  dqn.predict(obs, true, greedy);
  check_graph([&](PolicyGraph& g, const std::string& in) { dqn.export_policy(g, in, false); },
              greedy);
}

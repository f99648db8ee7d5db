#include "rlrun/algos/common/box_action_selection.hpp"

#include "rlrun/nn/policy_graph.hpp"

#include <algorithm>
#include <cmath>
#include <span>
#include <stdexcept>

#include "rlrun/algos/common/action_scaling.hpp"
#include "rlrun/algos/common/rng_streams.hpp"
#include "rlrun/core/state_dict.hpp"

namespace rlrun {

int BoxActionSelection::checked_action_dim(const AlgorithmSetup& setup, const std::string& id) {
  const Space& a = setup.action_space;
  if (!a.is_box())
    throw std::invalid_argument(
        id + ": action space " + a.describe() +
        " is not supported (Box only; wrap Discrete envs with DiscreteAsBox)");
  for (size_t i = 0; i < a.low().size(); ++i)
    if (!std::isfinite(a.low()[i]) || !std::isfinite(a.high()[i]) || !(a.low()[i] < a.high()[i]))
      throw std::invalid_argument(id + ": the action space " + a.describe() +
                                  " must have finite bounds low < high (the actor ends in tanh)");
  return a.flat_dim();
}

BoxActionSelection::BoxActionSelection(const AlgorithmSetup& setup, const ActionNoiseConfig& noise)
    : space_(setup.action_space),
      action_rng_(setup.seed ^ kActionStream),
      noise_rng_(setup.seed ^ kNoiseStream),
      noise_(noise, setup.action_space.flat_dim(), setup.n_envs) {}

void BoxActionSelection::sample_uniform(Eigen::Index n, Eigen::MatrixXf& env_actions,
                                        Eigen::MatrixXf& buffer_actions) {
  const int dim = space_.flat_dim();
  env_actions.resize(dim, n);
  for (Eigen::Index e = 0; e < n; ++e)
    space_.sample(action_rng_, std::span<float>(env_actions.col(e).data(), dim));
  scale_actions(space_, env_actions, buffer_actions);
}

void BoxActionSelection::add_noise(Eigen::MatrixXf& buffer_actions) {
  if (!noise_.enabled()) return;
  noise_.sample(noise_rng_, noise_sample_);
  buffer_actions = (buffer_actions + noise_sample_).cwiseMax(-1.0f).cwiseMin(1.0f);
}

void BoxActionSelection::to_env_actions(const Eigen::MatrixXf& scaled,
                                        Eigen::MatrixXf& env_actions) const {
  unscale_actions(space_, scaled, env_actions);
  for (Eigen::Index j = 0; j < env_actions.cols(); ++j)
    for (Eigen::Index i = 0; i < env_actions.rows(); ++i)
      env_actions(i, j) = std::clamp(env_actions(i, j), space_.low()[i], space_.high()[i]);
}

std::string BoxActionSelection::export_env_actions(PolicyGraph& graph,
                                                   const std::string& scaled) const {
  // low + 0.5 (a + 1) (high - low) = (a + 1) * (0.5 (high - low)) + low: the same float
  // (a product with 0.5 is exact).
  const int n = space_.flat_dim();
  const Eigen::Map<const Eigen::VectorXf> low(space_.low().data(), n),
      high(space_.high().data(), n);
  const Eigen::VectorXf half_range = 0.5f * (high - low);
  return graph.clamp(graph.affine(scaled, Eigen::VectorXf::Ones(n), half_range, low), low, high);
}

void BoxActionSelection::write_state(StateWriter out) const {
  out.put_rng("action_rng", action_rng_);
  out.put_rng("noise_rng", noise_rng_);
  put_matrix(out, "noise_state", noise_.state());
}

void BoxActionSelection::read_state(const StateReader& in) {
  in.get_rng("action_rng", action_rng_);
  in.get_rng("noise_rng", noise_rng_);
  Eigen::MatrixXf noise_state = noise_.state();
  get_matrix(in, "noise_state", noise_state);
  noise_.set_state(noise_state);
}

}  // namespace rlrun

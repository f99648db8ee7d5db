#pragma once
// SB3 BasePolicy.scale_action / unscale_action: Box actions live in [-1, 1] inside off-policy
// algorithms (tanh-squashed actors, replay buffer, noise) and in [low, high] in the env.
#include <Eigen/Core>

#include "rlrun/space.hpp"

namespace rlrun {

// [low, high] -> [-1, 1], column by column.
inline void scale_actions(const Space& space, const Eigen::Ref<const Eigen::MatrixXf>& actions,
                          Eigen::MatrixXf& scaled) {
  scaled.resize(actions.rows(), actions.cols());
  for (Eigen::Index j = 0; j < actions.cols(); ++j)
    for (Eigen::Index i = 0; i < actions.rows(); ++i) {
      const float low = space.low()[i], high = space.high()[i];
      scaled(i, j) = 2.0f * (actions(i, j) - low) / (high - low) - 1.0f;
    }
}

// [-1, 1] -> [low, high].
inline void unscale_actions(const Space& space, const Eigen::Ref<const Eigen::MatrixXf>& scaled,
                            Eigen::MatrixXf& actions) {
  actions.resize(scaled.rows(), scaled.cols());
  for (Eigen::Index j = 0; j < scaled.cols(); ++j)
    for (Eigen::Index i = 0; i < scaled.rows(); ++i) {
      const float low = space.low()[i], high = space.high()[i];
      actions(i, j) = low + 0.5f * (scaled(i, j) + 1.0f) * (high - low);
    }
}

}  // namespace rlrun

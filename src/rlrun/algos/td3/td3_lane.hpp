#pragma once
// One replica of TD3's networks (actor, actor_target, critics and their targets) that runs the
// forward and backward passes of one slice of a minibatch (algos/common/batch_lanes.hpp: TD3
// splits each training-sized minibatch over two lanes, one per core, and adds the replica's
// gradients to the primary lane's before the optimizer steps).
//
// Lane 0 holds the trained parameters; a replica lane copies the ones a pass reads from it
// first (pull_*). The passes write only the lane's own members and their own columns of y.
#include <Eigen/Core>
#include <vector>

#include "rlrun/algos/common/continuous_critic.hpp"
#include "rlrun/algos/common/replay_buffer.hpp"
#include "rlrun/algos/td3/td3_actor.hpp"

namespace rlrun {

class Td3Lane {
 public:
  // Parameters start at zero: call init (primary lane) or pull them (replicas).
  Td3Lane(int obs_dim, int action_dim, const std::vector<int>& net_arch, Activation activation,
          int n_critics);

  // SB3 TD3Policy._build order: actor (its target a copy), then each critic (target a copy);
  // torch's default Linear init.
  void init(Rng& rng);

  Td3Actor& actor() { return actor_; }
  const Td3Actor& actor() const { return actor_; }
  Td3Actor& actor_target() { return actor_target_; }
  const Td3Actor& actor_target() const { return actor_target_; }
  std::vector<ContinuousCritic>& critics() { return critics_; }
  const std::vector<ContinuousCritic>& critics() const { return critics_; }

  // Copies what critic_pass reads (actor_target, every critic and critic target) / what
  // actor_pass reads (actor, critic 1) from `primary`.
  void pull_critic_pass_params(const Td3Lane& primary);
  void pull_actor_pass_params(const Td3Lane& primary);

  // TD3.train's critic part for columns [begin, begin + count) of `batch`: target actions
  // smoothed with those columns of `noise`, y = r + (1 - done) gamma min_i Q_target_i written
  // to the same columns of `y`, then each critic's loss term and gradient (in its q().grads()),
  // normalised by inv_batch = 1 / whole batch size. Returns the slice's sum over critics.
  double critic_pass(const ReplayBatch& batch, Eigen::Index begin, Eigen::Index count,
                     const Eigen::MatrixXf& noise, float gamma, float inv_batch,
                     Eigen::MatrixXf& y);
  // TD3.train's actor loss -mean(Q_1(s, actor(s))) for those columns: returns the slice's part
  // and leaves its gradient in actor().net().grads() (zeroed first).
  double actor_pass(const ReplayBatch& batch, Eigen::Index begin, Eigen::Index count,
                    float inv_batch);

 private:
  void resize_workspaces(Eigen::Index count);

  int obs_dim_ = 0;
  int action_dim_ = 0;
  Td3Actor actor_, actor_target_;
  std::vector<ContinuousCritic> critics_;
  std::vector<const Eigen::MatrixXf*> target_values_;
  Eigen::MatrixXf next_actions_, obs_action_, next_obs_action_, obs_action_pi_, grad_q_;
};

}  // namespace rlrun

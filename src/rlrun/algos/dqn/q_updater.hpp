#pragma once
// One DQN gradient step, the body of SB3 dqn/dqn.py DQN.train's loop: TD targets from the
// target network, smooth L1 loss of Q(s, a), backward, th.nn.utils.clip_grad_norm_ and
// optimizer.step() (Adam with torch's defaults).
//
// Two lanes, for the second core: at rl-zoo sizes (256x256 networks, batch 64-128) DQN's time is
// all in these matrix products and one core's kernels already run near its FMA peak. A batch
// of at least kMinSplitBatch columns is split in two halves; lane k runs the target and online
// networks forward and the online network backward on its half, each lane through its own
// replica of both networks (an Mlp caches activations, so lanes cannot share one). Then each
// lane owns half of the parameter vector: it sums the two lanes' gradients there and, once the
// global gradient norm is known, clips, runs Adam (element-wise, so two optimizers over two
// halves equal one over all) and copies the new values into lane 1's replica. Lane 1 runs on
// ForkJoin's worker when that is on (RLRUN_THREADS=2), after lane 0 otherwise; the split
// depends on the batch size only, so a run is bit-identical either way.
#include <Eigen/Core>
#include <array>

#include "rlrun/algos/common/replay_buffer.hpp"
#include "rlrun/core/fork_join.hpp"
#include "rlrun/core/state_dict.hpp"
#include "rlrun/nn/adam.hpp"
#include "rlrun/nn/mlp.hpp"

namespace rlrun {

class QUpdater {
 public:
  // Smaller batches (tests, tiny configs) run in one lane: halves would be too thin to pay.
  static constexpr Eigen::Index kMinSplitBatch = 32;

  // q_net and q_net_target are updated in place and must outlive the updater (and stay where
  // they are).
  QUpdater(Mlp& q_net, Mlp& q_net_target, ForkJoin& fork_join = ForkJoin::shared(),
           AdamConfig adam = {});
  QUpdater(const QUpdater&) = delete;
  QUpdater& operator=(const QUpdater&) = delete;

  // Loss and gradient only: q_net's gradients are overwritten with d(loss)/d(params) for the
  // whole batch; returns the mean loss. The TD targets are kept (td_targets()).
  double loss_and_grad(const ReplayBatch& batch, float gamma);
  // A full gradient step with learning rate lr; returns the loss before the step.
  double step(const ReplayBatch& batch, float gamma, float max_grad_norm, float lr);

  // The networks were written outside step() (target update, load, tests): lane 1's replicas
  // re-copy them before their next use.
  void invalidate_q_net() { q_stale_ = true; }
  void invalidate_target() { target_stale_ = true; }

  const Eigen::RowVectorXf& td_targets() const { return targets_; }
  // Exact resume: the Adam moments of both parameter halves.
  void write_state(StateWriter out) const;
  void read_state(const StateReader& in);
  // The total gradient norm before clipping of the last step.
  float last_grad_norm() const { return last_grad_norm_; }

 private:
  struct Lane {
    Mlp* q = nullptr;  // lane 0: the real networks; lane 1: its own replicas
    Mlp* target = nullptr;
    Eigen::Index param_begin = 0, param_count = 0;  // this lane's half of the parameters
    Adam adam;                                      // over exactly that half
    double loss = 0.0, sum_sq = 0.0;
  };

  // Runs fn(lane) for lanes 0 and 1 (lane 1 on the worker) or for lane 0 alone.
  template <class F>
  void run_lanes(int lanes, F&& fn);
  void lane_loss(int k, int lanes);
  void lane_reduce(int k, int lanes);
  void lane_apply(int k);
  void sync_replicas();

  Mlp& q_net_;
  Mlp& q_net_target_;
  ForkJoin& fork_join_;
  Mlp q_replica_, target_replica_;
  std::array<Lane, 2> lanes_;
  int batch_lanes_ = 1;  // lanes used by the current batch's forward/backward
  bool q_stale_ = true, target_stale_ = true;

  // Arguments of the step in flight.
  const ReplayBatch* batch_ = nullptr;
  float gamma_ = 0.99f, clip_coef_ = 1.0f, lr_ = 0.0f;
  bool clip_ = false;

  Eigen::RowVectorXf targets_;  // 1 x batch, each lane writes its columns
  Eigen::MatrixXf grad_q_;      // n_actions x batch
  float last_grad_norm_ = 0.0f;
};

}  // namespace rlrun

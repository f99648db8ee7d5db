#pragma once
// One DQN gradient step, the body of SB3 dqn/dqn.py DQN.train's loop: TD targets from the
// target network, smooth L1 loss of Q(s, a), backward, th.nn.utils.clip_grad_norm_ and
// optimizer.step() (Adam with torch's defaults) — on one thread or data-parallel on several.
//
// Why threads: at rl-zoo sizes (256x256 networks, batch 64-128) DQN's time is all in these
// matrix products, and one core's kernels already run near its FMA peak, so the second core is
// the remaining speed-up. With n threads the batch is split into n column ranges; thread k
// runs the target and online networks forward and the online network backward on its range,
// through its own replica of both networks (an Mlp caches activations, so threads cannot
// share one). Then each thread owns 1/n of the parameter vector: it sums the replicas'
// gradients there, and after the global gradient norm is known, clips, runs Adam (element-wise,
// so n optimizers over n ranges equal one over all) and copies the new values to the replicas.
// Results are deterministic for a given thread count; different counts differ in the last bits
// of the gradient sums (summation order), as torch's own threading does.
#include <Eigen/Core>
#include <atomic>
#include <exception>
#include <memory>
#include <thread>
#include <vector>

#include "rlrun/algos/common/replay_buffer.hpp"
#include "rlrun/nn/adam.hpp"
#include "rlrun/nn/mlp.hpp"

namespace rlrun {

class QUpdater {
 public:
  // q_net and q_net_target are updated in place and must outlive the updater (and stay where
  // they are). n_threads >= 1; threads beyond the first start here and wait between steps.
  QUpdater(Mlp& q_net, Mlp& q_net_target, int n_threads, AdamConfig adam = {});
  ~QUpdater();
  QUpdater(const QUpdater&) = delete;
  QUpdater& operator=(const QUpdater&) = delete;

  // Loss and gradient only: q_net's gradients are overwritten with d(loss)/d(params) for the
  // whole batch; returns the mean loss. The TD targets are kept (td_targets()).
  double loss_and_grad(const ReplayBatch& batch, float gamma);
  // A full gradient step with learning rate lr; returns the loss before the step.
  double step(const ReplayBatch& batch, float gamma, float max_grad_norm, float lr);

  // The networks were written outside step() (target update, load, tests): replicas re-copy
  // them before the next use.
  void invalidate_q_net() { q_stale_ = true; }
  void invalidate_target() { target_stale_ = true; }

  int n_threads() const { return static_cast<int>(parts_.size()); }
  const Eigen::RowVectorXf& td_targets() const { return targets_; }
  // The total gradient norm before clipping of the last step.
  float last_grad_norm() const { return last_grad_norm_; }

 private:
  enum class Phase { kLoss, kReduce, kApply, kStop };
  // What one thread owns.
  struct Part {
    Mlp* q = nullptr;  // thread 0: the real networks; others: their own replicas
    Mlp* target = nullptr;
    Mlp q_copy, target_copy;
    Eigen::Index param_begin = 0, param_count = 0;  // this thread's share of the parameters
    Adam adam;                                      // over exactly that share
    double loss = 0.0, sum_sq = 0.0;
  };

  void sync_replicas();
  // Runs `phase` on every thread (thread 0 is the caller) and returns when all are done.
  void run_all(Phase phase);
  void run_part(Phase phase, int k);
  void worker_loop(int k);

  Mlp& q_net_;
  Mlp& q_net_target_;
  std::vector<std::unique_ptr<Part>> parts_;
  std::vector<std::thread> workers_;
  bool q_stale_ = true, target_stale_ = true;

  // Arguments of the phase in flight (written before the release of generation_).
  Phase phase_ = Phase::kLoss;
  const ReplayBatch* batch_ = nullptr;
  float gamma_ = 0.99f, clip_coef_ = 1.0f, lr_ = 0.0f;
  bool clip_ = false;
  std::atomic<uint32_t> generation_{0};
  std::atomic<int> pending_{0};
  std::vector<std::exception_ptr> errors_;  // a worker's exception, rethrown by run_all

  Eigen::RowVectorXf targets_;  // 1 x batch, each thread writes its columns
  Eigen::MatrixXf grad_q_;      // n_actions x batch
  float last_grad_norm_ = 0.0f;
};

}  // namespace rlrun

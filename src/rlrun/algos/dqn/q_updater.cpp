#include "rlrun/algos/dqn/q_updater.hpp"

#include "rlrun/algos/common/training_state.hpp"

#include <algorithm>
#include <cmath>

#include "rlrun/algos/dqn/dqn_loss.hpp"

namespace rlrun {

namespace {

// Sum of squares in float chunks (vectorised) accumulated in double: the clipping coefficient
// needs no more (torch itself reduces in float32).
double sum_of_squares(const float* g, Eigen::Index n) {
  constexpr Eigen::Index kChunk = 4096;
  double sum = 0.0;
  for (Eigen::Index i = 0; i < n; i += kChunk)
    sum += Eigen::Map<const Eigen::VectorXf>(g + i, std::min(kChunk, n - i)).squaredNorm();
  return sum;
}

}  // namespace

QUpdater::QUpdater(Mlp& q_net, Mlp& q_net_target, ForkJoin& fork_join, AdamConfig adam)
    : q_net_(q_net),
      q_net_target_(q_net_target),
      fork_join_(fork_join),
      q_replica_(q_net),
      target_replica_(q_net_target) {
  lanes_[0].q = &q_net_;
  lanes_[0].target = &q_net_target_;
  lanes_[1].q = &q_replica_;
  lanes_[1].target = &target_replica_;
  // Halves start on a 64-byte line (16 floats), so the lanes never write the same cache line.
  const Eigen::Index n_params = q_net.num_params();
  const Eigen::Index split = n_params / 2 / 16 * 16;
  lanes_[0].param_count = split;
  lanes_[1].param_begin = split;
  lanes_[1].param_count = n_params - split;
  for (Lane& lane : lanes_)
    lane.adam = Adam({ParamBlock{q_net_.params().data() + lane.param_begin,
                                 q_net_.grads().data() + lane.param_begin, lane.param_count}},
                     adam);
}

template <class F>
void QUpdater::run_lanes(int lanes, F&& fn) {
  if (lanes == 1) {
    fn(0);
    return;
  }
  fork_join_.run([&] { fn(0); }, [&] { fn(1); });
}

void QUpdater::lane_loss(int k, int lanes) {
  Lane& lane = lanes_[k];
  const Eigen::Index batch = batch_->obs.cols();
  const Eigen::Index c0 = k == 0 ? 0 : batch / 2;
  const Eigen::Index cols = lanes == 1 ? batch : (k == 0 ? batch / 2 : batch - batch / 2);
  const Eigen::MatrixXf& next_q = lane.target->forward(batch_->next_obs.middleCols(c0, cols));
  dqn_td_targets(next_q, batch_->rewards.segment(c0, cols), batch_->dones.segment(c0, cols), gamma_,
                 targets_.segment(c0, cols));
  const Eigen::MatrixXf& q = lane.q->forward(batch_->obs.middleCols(c0, cols));
  lane.loss = dqn_huber_loss(q, batch_->actions.middleCols(c0, cols), targets_.segment(c0, cols),
                             grad_q_.middleCols(c0, cols), batch);
  lane.q->zero_grad();
  lane.q->backward(grad_q_.middleCols(c0, cols));
}

void QUpdater::lane_reduce(int k, int lanes) {
  Lane& lane = lanes_[k];
  Eigen::Map<Eigen::VectorXf> total(q_net_.grads().data() + lane.param_begin, lane.param_count);
  if (lanes == 2)
    total += Eigen::Map<const Eigen::VectorXf>(q_replica_.grads().data() + lane.param_begin,
                                               lane.param_count);
  lane.sum_sq = sum_of_squares(total.data(), lane.param_count);
}

void QUpdater::lane_apply(int k) {
  Lane& lane = lanes_[k];
  if (clip_)
    Eigen::Map<Eigen::VectorXf>(q_net_.grads().data() + lane.param_begin, lane.param_count) *=
        clip_coef_;
  lane.adam.step(lr_);
  Eigen::Map<Eigen::VectorXf>(q_replica_.params().data() + lane.param_begin, lane.param_count) =
      Eigen::Map<const Eigen::VectorXf>(q_net_.params().data() + lane.param_begin,
                                        lane.param_count);
}

void QUpdater::sync_replicas() {
  if (q_stale_) q_replica_.params() = q_net_.params();
  if (target_stale_) target_replica_.params() = q_net_target_.params();
  q_stale_ = target_stale_ = false;
}

double QUpdater::loss_and_grad(const ReplayBatch& batch, float gamma) {
  sync_replicas();
  const Eigen::Index size = batch.obs.cols();
  if (targets_.size() != size) targets_.resize(size);
  if (grad_q_.rows() != q_net_.out_dim() || grad_q_.cols() != size)
    grad_q_.resize(q_net_.out_dim(), size);
  batch_ = &batch;
  gamma_ = gamma;
  batch_lanes_ = size >= kMinSplitBatch ? 2 : 1;
  run_lanes(batch_lanes_, [this](int k) { lane_loss(k, batch_lanes_); });
  // Both halves of the parameter vector, whatever the batch used.
  run_lanes(2, [this](int k) { lane_reduce(k, batch_lanes_); });
  batch_ = nullptr;
  return batch_lanes_ == 2 ? lanes_[0].loss + lanes_[1].loss : lanes_[0].loss;
}

double QUpdater::step(const ReplayBatch& batch, float gamma, float max_grad_norm, float lr) {
  const double loss = loss_and_grad(batch, gamma);
  // th.nn.utils.clip_grad_norm_: total = ||g||_2 over all parameters, coef = max_norm /
  // (total + 1e-6), applied when below 1 (a NaN norm propagates, as torch's default does).
  last_grad_norm_ = static_cast<float>(std::sqrt(lanes_[0].sum_sq + lanes_[1].sum_sq));
  clip_coef_ = max_grad_norm / (last_grad_norm_ + 1e-6f);
  clip_ = clip_coef_ < 1.0f || std::isnan(clip_coef_);
  lr_ = lr;
  run_lanes(2, [this](int k) { lane_apply(k); });
  return loss;
}

void QUpdater::write_state(StateWriter out) const {
  for (size_t k = 0; k < lanes_.size(); ++k) write_adam(out.sub("adam" + std::to_string(k)), lanes_[k].adam);
}

void QUpdater::read_state(const StateReader& in) {
  for (size_t k = 0; k < lanes_.size(); ++k) read_adam(in.sub("adam" + std::to_string(k)), lanes_[k].adam);
}

}  // namespace rlrun

#include "rlrun/algos/dqn/q_updater.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <stdexcept>

#include "rlrun/algos/dqn/dqn_loss.hpp"

namespace rlrun {

namespace {

// Spins before a thread blocks in the kernel: the waits between the phases of one step are a
// few microseconds, far below a futex round trip; the waits between train() calls are long.
constexpr int kSpins = 2000;

inline void cpu_relax() {
#if defined(__x86_64__) || defined(__i386__)
  __builtin_ia32_pause();
#endif
}

template <class T>
void wait_while_equal(const std::atomic<T>& a, T value) {
  for (int i = 0; i < kSpins; ++i) {
    if (a.load(std::memory_order_acquire) != value) return;
    cpu_relax();
  }
  while (a.load(std::memory_order_acquire) == value) a.wait(value, std::memory_order_acquire);
}

void wait_until_zero(const std::atomic<int>& a) {
  for (int i = 0; i < kSpins; ++i) {
    if (a.load(std::memory_order_acquire) == 0) return;
    cpu_relax();
  }
  for (int v; (v = a.load(std::memory_order_acquire)) != 0;) a.wait(v, std::memory_order_acquire);
}

// Sum of squares in float chunks (vectorised) accumulated in double: the clipping coefficient
// needs no more (torch itself reduces in float32).
double sum_of_squares(const float* g, Eigen::Index n) {
  constexpr Eigen::Index kChunk = 4096;
  double sum = 0.0;
  for (Eigen::Index i = 0; i < n; i += kChunk)
    sum += Eigen::Map<const Eigen::VectorXf>(g + i, std::min(kChunk, n - i)).squaredNorm();
  return sum;
}

// Thread k's share [begin, end) of n items in `parts` pieces; starts aligned to `align`.
Eigen::Index share_begin(Eigen::Index n, int parts, int k, Eigen::Index align) {
  if (k == 0) return 0;
  if (k == parts) return n;
  return (n * k / parts) / align * align;
}

}  // namespace

QUpdater::QUpdater(Mlp& q_net, Mlp& q_net_target, int n_threads, AdamConfig adam)
    : q_net_(q_net), q_net_target_(q_net_target) {
  if (n_threads < 1) throw std::invalid_argument("QUpdater: n_threads must be >= 1");
  const Eigen::Index n_params = q_net.num_params();
  for (int k = 0; k < n_threads; ++k) {
    auto part = std::make_unique<Part>();
    if (k == 0) {
      part->q = &q_net_;
      part->target = &q_net_target_;
    } else {
      part->q_copy = q_net_;
      part->target_copy = q_net_target_;
      part->q = &part->q_copy;
      part->target = &part->target_copy;
    }
    // 16 floats = one 64-byte cache line, so that no two threads write the same line.
    part->param_begin = share_begin(n_params, n_threads, k, 16);
    part->param_count = share_begin(n_params, n_threads, k + 1, 16) - part->param_begin;
    part->adam = Adam({ParamBlock{q_net_.params().data() + part->param_begin,
                                  q_net_.grads().data() + part->param_begin, part->param_count}},
                      adam);
    parts_.push_back(std::move(part));
  }
  errors_.resize(n_threads);
  for (int k = 1; k < n_threads; ++k) workers_.emplace_back([this, k] { worker_loop(k); });
}

QUpdater::~QUpdater() {
  if (workers_.empty()) return;
  phase_ = Phase::kStop;
  generation_.fetch_add(1, std::memory_order_release);
  generation_.notify_all();
  for (std::thread& t : workers_) t.join();
}

void QUpdater::worker_loop(int k) {
  uint32_t seen = 0;
  for (;;) {
    wait_while_equal(generation_, seen);
    seen = generation_.load(std::memory_order_acquire);
    const Phase phase = phase_;
    if (phase == Phase::kStop) return;
    try {
      run_part(phase, k);
    } catch (...) {
      errors_[k] = std::current_exception();
    }
    if (pending_.fetch_sub(1, std::memory_order_acq_rel) == 1) pending_.notify_one();
  }
}

void QUpdater::run_all(Phase phase) {
  if (workers_.empty()) {
    run_part(phase, 0);
    return;
  }
  phase_ = phase;
  pending_.store(static_cast<int>(workers_.size()), std::memory_order_relaxed);
  generation_.fetch_add(1, std::memory_order_release);
  generation_.notify_all();
  std::exception_ptr own;
  try {
    run_part(phase, 0);
  } catch (...) {
    own = std::current_exception();
  }
  wait_until_zero(pending_);
  if (own) std::rethrow_exception(own);
  for (std::exception_ptr& e : errors_) {
    if (!e) continue;
    std::exception_ptr error = e;
    e = nullptr;
    std::rethrow_exception(error);
  }
}

void QUpdater::run_part(Phase phase, int k) {
  Part& part = *parts_[k];
  const int n = n_threads();
  switch (phase) {
    case Phase::kLoss: {
      const Eigen::Index batch = batch_->obs.cols();
      const Eigen::Index c0 = share_begin(batch, n, k, 1);
      const Eigen::Index cols = share_begin(batch, n, k + 1, 1) - c0;
      part.q->zero_grad();
      part.loss = 0.0;
      if (cols == 0) return;  // fewer samples than threads
      const Eigen::MatrixXf& next_q = part.target->forward(batch_->next_obs.middleCols(c0, cols));
      dqn_td_targets(next_q, batch_->rewards.segment(c0, cols), batch_->dones.segment(c0, cols),
                     gamma_, targets_.segment(c0, cols));
      const Eigen::MatrixXf& q = part.q->forward(batch_->obs.middleCols(c0, cols));
      part.loss = dqn_huber_loss(q, batch_->actions.middleCols(c0, cols),
                                 targets_.segment(c0, cols), grad_q_.middleCols(c0, cols), batch);
      part.q->backward(grad_q_.middleCols(c0, cols));
      return;
    }
    case Phase::kReduce: {
      float* g = q_net_.grads().data() + part.param_begin;
      Eigen::Map<Eigen::VectorXf> total(g, part.param_count);
      for (int j = 1; j < n; ++j)
        total += Eigen::Map<const Eigen::VectorXf>(parts_[j]->q->grads().data() + part.param_begin,
                                                   part.param_count);
      part.sum_sq = sum_of_squares(g, part.param_count);
      return;
    }
    case Phase::kApply: {
      if (clip_)
        Eigen::Map<Eigen::VectorXf>(q_net_.grads().data() + part.param_begin, part.param_count) *=
            clip_coef_;
      part.adam.step(lr_);
      const Eigen::Map<const Eigen::VectorXf> fresh(q_net_.params().data() + part.param_begin,
                                                    part.param_count);
      for (int j = 1; j < n; ++j)
        Eigen::Map<Eigen::VectorXf>(parts_[j]->q->params().data() + part.param_begin,
                                    part.param_count) = fresh;
      return;
    }
    case Phase::kStop:
      return;
  }
}

void QUpdater::sync_replicas() {
  for (int k = 1; k < n_threads(); ++k) {
    if (q_stale_) parts_[k]->q->params() = q_net_.params();
    if (target_stale_) parts_[k]->target->params() = q_net_target_.params();
  }
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
  run_all(Phase::kLoss);
  run_all(Phase::kReduce);
  batch_ = nullptr;
  double loss = 0.0;
  for (const auto& part : parts_) loss += part->loss;
  return loss;
}

double QUpdater::step(const ReplayBatch& batch, float gamma, float max_grad_norm, float lr) {
  const double loss = loss_and_grad(batch, gamma);
  // th.nn.utils.clip_grad_norm_: total = ||g||_2 over all parameters, coef = max_norm /
  // (total + 1e-6), applied when below 1 (a NaN norm propagates, as torch's default does).
  double sum_sq = 0.0;
  for (const auto& part : parts_) sum_sq += part->sum_sq;
  last_grad_norm_ = static_cast<float>(std::sqrt(sum_sq));
  clip_coef_ = max_grad_norm / (last_grad_norm_ + 1e-6f);
  clip_ = clip_coef_ < 1.0f || std::isnan(clip_coef_);
  lr_ = lr;
  run_all(Phase::kApply);
  return loss;
}

}  // namespace rlrun

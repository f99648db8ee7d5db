#pragma once
// An Mlp whose passes over a training minibatch use the run's threads: data parallelism over
// the batch's columns (batch_split.hpp cuts them into 2 to 16 parts by size). The first part
// runs through the network itself, each further part through a replica, each on whichever
// thread of the pool takes it. A replica reads the network's parameters in place (it has none
// of its own) and keeps its own activations and gradient; backward adds the parts' gradients
// to the network's in part order once all are done, so grads() ends as ((grads + part 0's) +
// part 1's) + ..., the same bits with any number of threads. Callers (SAC, TD3, DQN) pass whole
// minibatches and never see the parts.
//
// Like Mlp: a backward belongs to the last forward through the same SplitMlp; not thread-safe
// otherwise. Between passes the parameters may change freely (optimizer steps, Polyak updates,
// loading): the replica has no copy to refresh.
#include <Eigen/Core>
#include <vector>

#include "rlrun/core/thread_pool.hpp"
#include "rlrun/nn/mlp.hpp"

namespace rlrun {

class SplitMlp {
 public:
  SplitMlp() = default;
  // Parameters start at zero (see Mlp). Throws std::invalid_argument for non-positive sizes.
  // `pool` runs the halves (null: both on the calling thread, one after the other).
  SplitMlp(int in_dim, std::vector<int> hidden, int out_dim, Activation act,
           ThreadPool* pool = nullptr);
  explicit SplitMlp(Mlp net, ThreadPool* pool = nullptr);
  // Copies the network; the copy makes its own replicas when a pass first needs them (acting
  // copies, whose batches are small, never do).
  SplitMlp(const SplitMlp& other) : net_(other.net_), pool_(other.pool_) {}
  SplitMlp& operator=(const SplitMlp& other);

  // The network: parameters, gradients, shape, and unsplit passes.
  Mlp& net() { return net_; }
  const Mlp& net() const { return net_; }
  Eigen::VectorXf& params() { return net_.params(); }
  const Eigen::VectorXf& params() const { return net_.params(); }
  Eigen::VectorXf& grads() { return net_.grads(); }
  const Eigen::VectorXf& grads() const { return net_.grads(); }
  void zero_grad() { net_.zero_grad(); }

  // Mlp::forward of a whole batch x (in_dim x n): out_dim x n, valid until the next forward.
  const Eigen::MatrixXf& forward(const Eigen::Ref<const Eigen::MatrixXf>& x);
  const Eigen::MatrixXf& output() const { return parts_ == 1 ? net_.output() : output_; }
  // Mlp::last_hidden of the whole last forward (the parts gathered into one matrix on a split
  // pass; only callers that need the latent features pay for the copy).
  const Eigen::MatrixXf& last_hidden();
  // Mlp::backward of the last forward (dL/doutput, out_dim x n): ADDS the whole batch's
  // parameter gradient to grads().
  void backward(const Eigen::Ref<const Eigen::MatrixXf>& grad_output);
  // torch's optimizer.zero_grad(); loss.backward(): grads() becomes the whole batch's gradient
  // (the same bits as zero_grad() then backward(), the zeroing done by each part's thread).
  // grad_last_hidden (optional): a further dL/d(last_hidden()), as in Mlp::backward.
  // grad_input (optional): resized to in_dim x n, receives dL/dx of the same pass (a features
  // extractor in front of the network learns from it).
  void zero_grad_and_backward(const Eigen::Ref<const Eigen::MatrixXf>& grad_output,
                              const Eigen::MatrixXf* grad_last_hidden = nullptr,
                              Eigen::MatrixXf* grad_input = nullptr);
  // Mlp::backward_input of the last forward: rows [first_input_row, in_dim) of dL/dx, for the
  // whole batch, into grad_input; grads() is left unchanged.
  void backward_input(const Eigen::Ref<const Eigen::MatrixXf>& grad_output,
                      Eigen::MatrixXf& grad_input, int first_input_row = 0);

 private:
  // The network that computes part k: the network itself for part 0, else replica k - 1 (made
  // on first use).
  Mlp& part_net(int k);
  void backward_parts(const Eigen::Ref<const Eigen::MatrixXf>& grad_output, bool zero_first,
                      const Eigen::MatrixXf* grad_last_hidden = nullptr,
                      Eigen::MatrixXf* grad_input = nullptr);
  // Before a split backward of n columns: W^T of every layer the parts carry the input
  // gradient through, transposed once into net_ (two threads a part of the rows each) for all
  // parts to read, rather than once per part (DQN's 4-256-256-2 update at batch 64 on a Zen 5:
  // 227 -> 214 us on one core). With the network's input gradient from row first_input_row
  // when input_gradient. Only a copy: the same bits either way.
  void transpose_for_parts(Eigen::Index n, bool input_gradient, int first_input_row = 0);

  Mlp net_;
  std::vector<Mlp> replicas_;  // parts 1, 2, ... of the largest split so far
  ThreadPool* pool_ = nullptr;
  int parts_ = 1;                // of the last forward
  Eigen::MatrixXf output_;       // the last split forward's output, all parts
  Eigen::MatrixXf last_hidden_;  // last_hidden() of a split forward, all parts
};

}  // namespace rlrun

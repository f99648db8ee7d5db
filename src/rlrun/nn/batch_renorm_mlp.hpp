#pragma once
// SB3's create_mlp with pre_linear_modules=[BatchRenorm1d] (stable_baselines3/common/
// torch_layers.py, SB3 >= 2.4), the networks of sb3-contrib 2.4's CrossQ (crossq/policies.py):
//   [BatchRenorm(in)] Linear(in, h0) act [BatchRenorm(h0)] Linear(h0, h1) act ...
//   [BatchRenorm(h_last)] Linear(h_last, out)            (out_dim > 0: a critic's Q-network)
// or, with out_dim == 0, the hidden layers only and, with batch norm and hidden layers, one more
// BatchRenorm(h_last) at the end (CrossQ Actor's latent_pi: `latent_pi_net.append(...)`).
// Without batch_norm it is the plain create_mlp.
//
// Layout: one sample per column. Each Linear is a one-layer SplitMlp, so a training minibatch's
// products use the run's threads (same bits on any number); the batch statistics need the whole
// batch and are computed between them. forward(x, training) runs the BatchRenorm layers in
// train mode (batch statistics, running statistics updated) or eval mode (running statistics);
// a backward belongs to the last forward.
#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "rlrun/core/tensor.hpp"
#include "rlrun/core/thread_pool.hpp"
#include "rlrun/nn/activation.hpp"
#include "rlrun/nn/batch_renorm.hpp"
#include "rlrun/nn/mlp.hpp"
#include "rlrun/nn/param_block.hpp"
#include "rlrun/nn/split_mlp.hpp"
#include "rlrun/rng.hpp"

namespace rlrun {

class BatchRenormMlp {
 public:
  BatchRenormMlp() = default;
  // Parameters: Linear layers at zero (call init_torch_default), BatchRenorm at scale 1, bias 0.
  // Throws std::invalid_argument for non-positive sizes.
  BatchRenormMlp(int in_dim, std::vector<int> hidden, int out_dim, Activation act, bool batch_norm,
                 const BatchRenormOptions& bn, ThreadPool* pool = nullptr);

  int in_dim() const { return in_dim_; }
  // The output width: out_dim, or with out_dim == 0 the last hidden width (in_dim without any).
  int out_dim() const { return out_dim_; }
  const std::vector<int>& hidden() const { return hidden_; }
  Activation activation() const { return act_; }
  int num_linear() const { return static_cast<int>(stages_.size()); }
  const Mlp& linear(int l) const { return stages_[l].linear.net(); }
  Mlp& linear(int l) { return stages_[l].linear.net(); }
  // The BatchRenorm before Linear l (null without batch norm), and the trailing one.
  const BatchRenorm* norm(int l) const { return stages_[l].norm ? &*stages_[l].norm : nullptr; }
  const BatchRenorm* trailing_norm() const { return trailing_ ? &*trailing_ : nullptr; }
  // Multiply-adds of one sample's forward pass.
  Eigen::Index multiply_adds_per_column() const;

  // torch.nn.Linear.reset_parameters on every Linear, first to last (BatchRenorm has no random
  // init).
  void init_torch_default(Rng& rng);
  // Every parameter tensor as optimizer blocks (BatchRenorm scale/bias, Linear weight/bias).
  std::vector<ParamBlock> blocks();
  void zero_grad();
  // The same network's parameters and running statistics (an acting copy's refresh).
  void copy_state_from(const BatchRenormMlp& other);

  // The network on x (in_dim x n), BatchRenorm in train or eval mode; returns out_dim() x n.
  const Eigen::MatrixXf& forward(const Eigen::Ref<const Eigen::MatrixXf>& x, bool training);
  const Eigen::MatrixXf& output() const;
  // optimizer.zero_grad(); loss.backward() for dL/doutput of the last forward: every parameter
  // gradient; grad_input (optional) receives dL/dx (in_dim x n).
  void zero_grad_and_backward(const Eigen::Ref<const Eigen::MatrixXf>& grad_output,
                              Eigen::MatrixXf* grad_input = nullptr);
  // Rows [first_input_row, in_dim) of dL/dx of the last forward, which must have been in eval
  // mode (std::logic_error otherwise). Parameter gradients are left as they are (an actor loss
  // through the critic: torch adds it to the critic's .grad, which the critic's
  // optimizer.zero_grad() discards before it is used).
  void backward_input(const Eigen::Ref<const Eigen::MatrixXf>& grad_output,
                      Eigen::MatrixXf& grad_input, int first_input_row = 0);

  // The eval-mode network as a plain Mlp: each BatchRenorm's affine map y = a x + c folded into
  // the next Linear (W diag(a), b + W c). `head` (one linear layer, out_dim == 0 only) is
  // stacked on top with the trailing BatchRenorm folded into it. Export and tests.
  Mlp folded(const Mlp* head = nullptr) const;

  // torch Sequential names under `prefix`: <prefix>.<k>.scale/bias/ra_mean/ra_var/steps for
  // BatchRenorm modules and <prefix>.<k>.weight/bias for Linear ones, k counting every module
  // (activations too). Throws std::runtime_error for missing or misshapen tensors.
  void save(const std::string& prefix, TensorMap& tensors) const;
  void load(const std::string& prefix, const TensorMap& tensors);

 private:
  struct Stage {
    std::optional<BatchRenorm> norm;
    SplitMlp linear;         // one Linear layer
    bool activated = false;  // an activation follows (hidden layers)
    Eigen::MatrixXf act;     // its output in the last forward
  };
  // The modules' torch Sequential indices: of stage l's BatchRenorm (-1: none) and Linear.
  void module_indices(int l, int& norm_index, int& linear_index) const;
  int trailing_index() const;
  // dL/d(input of stage l) from dL/d(output of stage l) (in place in grad_).
  void backward_stage(int l, bool param_grads, bool input_gradient);

  int in_dim_ = 0, out_dim_ = 0;
  std::vector<int> hidden_;
  Activation act_ = Activation::kReLU;
  std::vector<Stage> stages_;
  std::optional<BatchRenorm> trailing_;
  Eigen::MatrixXf input_copy_;  // identity network (no stage): the last input
  Eigen::MatrixXf grad_, grad_linear_in_;
};

}  // namespace rlrun

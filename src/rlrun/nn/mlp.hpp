#pragma once
// A fully connected network: Linear -> act -> ... -> Linear, the last layer linear. This is
// SB3's mlp_extractor (common/torch_layers.py create_mlp / MlpExtractor) with the action_net or
// value_net head stacked on top, i.e. one of the two towers of an ActorCriticPolicy, a SAC
// actor's latent_pi + mu, or a ContinuousCritic's q-network.
//
// Layout: one sample per column; forward maps (in_dim x batch) to (out_dim x batch).
// Parameters: ALL weights and biases live in one contiguous params_ vector (per layer: the
// out x in weight, column-major, then the out-long bias) with a same-sized grads_. So copying an
// Mlp, `target.params() = online.params()`, Polyak averaging and optimizers are plain vector
// operations. Per-layer views are Eigen::Maps built on demand from stored offsets; no pointer
// into params_ is ever stored, so an Mlp is safely copyable and movable.
// Note for export: torch stores Linear.weight row-major (out, in); weight(l) is the same matrix
// stored column-major, i.e. a Fortran-order (out, in) array.
// Speed: the products run on register-blocked kernels with bias + activation fused
// (dense_kernels.hpp); no allocation happens in forward/backward while the batch size is
// unchanged.
// One forward, then its backward: forward overwrites the cached activations, so run the
// backward of one batch before the next forward through the same Mlp (SAC's target networks are
// separate Mlp copies anyway). Not thread-safe: each thread needs its own Mlp (SplitMlp runs
// part of a batch through a replica that reads this Mlp's parameters in place).
#include <Eigen/Core>
#include <vector>

#include "rlrun/nn/activation.hpp"
#include "rlrun/nn/param_block.hpp"
#include "rlrun/rng.hpp"

namespace rlrun {

class Mlp {
 public:
  Mlp() = default;
  // hidden may be empty (a single linear layer). Parameters start at zero: call
  // init_orthogonal (SB3's init) or write params() directly. Throws std::invalid_argument for
  // non-positive sizes.
  Mlp(int in_dim, std::vector<int> hidden, int out_dim, Activation act);

  int in_dim() const { return dims_.empty() ? 0 : dims_.front(); }
  int out_dim() const { return dims_.empty() ? 0 : dims_.back(); }
  const std::vector<int>& hidden() const { return hidden_; }
  Activation activation() const { return act_; }
  int num_layers() const { return static_cast<int>(w_offset_.size()); }
  // Input and output width of layer l.
  int layer_in(int layer) const { return dims_[layer]; }
  int layer_out(int layer) const { return dims_[layer + 1]; }
  // Multiply-adds of one sample's forward pass (sum of in * out over the layers).
  Eigen::Index multiply_adds_per_column() const {
    Eigen::Index total = 0;
    for (size_t l = 0; l + 1 < dims_.size(); ++l) total += Eigen::Index{dims_[l]} * dims_[l + 1];
    return total;
  }
  Eigen::Index num_params() const { return params_.size(); }

  Eigen::VectorXf& params() { return params_; }
  const Eigen::VectorXf& params() const { return params_; }
  Eigen::VectorXf& grads() { return grads_; }
  const Eigen::VectorXf& grads() const { return grads_; }
  // The whole network as one optimizer block (valid until this Mlp is moved or reassigned).
  ParamBlock block() { return {params_.data(), grads_.data(), params_.size()}; }
  void zero_grad() { grads_.setZero(); }

  // Views of layer l's parameters and gradients; weight is (out x in) like torch's.
  Eigen::Map<Eigen::MatrixXf> weight(int layer);
  Eigen::Map<const Eigen::MatrixXf> weight(int layer) const;
  Eigen::Map<Eigen::VectorXf> bias(int layer);
  Eigen::Map<const Eigen::VectorXf> bias(int layer) const;
  Eigen::Map<Eigen::MatrixXf> weight_grad(int layer);
  Eigen::Map<const Eigen::MatrixXf> weight_grad(int layer) const;
  Eigen::Map<Eigen::VectorXf> bias_grad(int layer);
  Eigen::Map<const Eigen::VectorXf> bias_grad(int layer) const;

  // torch.nn.init.orthogonal_ on every weight (hidden_gain for all but the last layer,
  // output_gain for the last), zero biases: SB3 ActorCriticPolicy uses sqrt(2) and 0.01 (policy)
  // or 1 (value). Layers are initialised first to last from rng.
  void init_orthogonal(Rng& rng, float hidden_gain, float output_gain);
  // torch.nn.Linear.reset_parameters, i.e. what SB3's off-policy networks (SAC, TD3, DQN) get,
  // since they never call init_weights: kaiming_uniform_(a = sqrt(5)) on the weight and
  // U(-1/sqrt(fan_in), 1/sqrt(fan_in)) on the bias, which both reduce to that same uniform law.
  void init_torch_default(Rng& rng);

  // Runs the network on x (in_dim x batch) and returns the output (out_dim x batch). Keeps a
  // copy of x and every layer's output for backward (with GELU also every hidden layer's
  // pre-activation); the buffers are reused, so no allocation happens while the batch size
  // stays the same. The reference stays valid until the next call.
  const Eigen::MatrixXf& forward(const Eigen::Ref<const Eigen::MatrixXf>& x);
  // The output of the last forward.
  const Eigen::MatrixXf& output() const { return acts_.back(); }
  // The input of the output layer in the last forward: the last hidden layer's activations
  // (SB3's latent_pi, what gSDE's noise reads), or the network's input without hidden layers.
  const Eigen::MatrixXf& last_hidden() const { return acts_[acts_.size() - 2]; }

  // Backpropagates dL/doutput (out_dim x batch of the last forward; any outer stride) and ADDS
  // the parameter gradients to grads() (so several losses through the same network sum, as in
  // torch before optimizer.zero_grad()). If grad_input is given it is resized to in_dim x batch
  // and receives dL/dx (e.g. dQ/da for SAC's actor loss through the critic).
  // grad_last_hidden, if given, is a further dL/d(last_hidden()) (hidden x batch) from a loss
  // that reads the latent features directly (gSDE with learn_features); it is ignored without
  // hidden layers (the input has no parameters).
  void backward(const Eigen::Ref<const Eigen::MatrixXf>& grad_output,
                Eigen::MatrixXf* grad_input = nullptr,
                const Eigen::MatrixXf* grad_last_hidden = nullptr);
  // Backpropagates dL/doutput of the last forward to the input only: grad_input is resized to
  // (in_dim - first_input_row) x batch and receives rows [first_input_row, in_dim) of dL/dx;
  // grads() is left unchanged. This is about half of backward()'s work: what an actor loss
  // through a critic needs (SB3's TD3/SAC actor_loss.backward() also fills the critic's .grad,
  // but the critic's optimizer.zero_grad() discards it before it is ever used).
  void backward_input(const Eigen::Ref<const Eigen::MatrixXf>& grad_output,
                      Eigen::MatrixXf& grad_input, int first_input_row = 0);
  // Forward-mode derivative (a Jacobian-vector product) at the last forward: d_output
  // (out_dim x batch) = d(output)/d(params) * d_params, for a direction d_params laid out as
  // params() and a fixed input. TRPO's Fisher-vector products (algos/trpo/) use it; defined in
  // mlp_jvp.cpp.
  void jvp(const Eigen::Ref<const Eigen::VectorXf>& d_params, Eigen::MatrixXf& d_output) const;

 private:
  friend class SplitMlp;
  // The passes with the parameters at `p` (num_params() floats in this Mlp's layout): its own,
  // or, for a SplitMlp's replica, the primary network's.
  const Eigen::MatrixXf& forward_with(const float* p, const Eigen::Ref<const Eigen::MatrixXf>& x);
  // The layers' backward pass: parameter gradients when param_grads, dL/dx rows
  // [first_input_row, in_dim) into grad_input when it is given ((in_dim - first_input_row) x
  // batch, column-major, leading dimension its row count; e.g. columns of a larger matrix).
  // grad_hidden (optional): dL/d(last_hidden()) added before the last hidden layer's
  // activation derivative, column-major with leading dimension ld_grad_hidden.
  // transposed_by (optional): an Mlp whose wt_ already holds W^T of every layer this pass
  // would transpose (a SplitMlp transposes once for both halves); else the pass transposes.
  void backward_pass(const float* p, const Eigen::Ref<const Eigen::MatrixXf>& grad_output,
                     bool param_grads, float* grad_input, int first_input_row,
                     const float* grad_hidden = nullptr, Eigen::Index ld_grad_hidden = 0,
                     const Mlp* transposed_by = nullptr);
  // Whether backward_pass carries dL/d(input) through a layer with its W^T (rather than dot
  // products against W's columns) when `rows` rows of that gradient are wanted (a hidden
  // input: all in_dim of them) for a batch of `batch` columns.
  static bool uses_transposed_weight(Eigen::Index rows, Eigen::Index batch);
  // Rows [begin, begin + count) of wt_[l] = W_l^T, from the parameters at p: a part of the
  // transpose, so that two cores can share one.
  void transpose_weight_rows(const float* p, int l, Eigen::Index begin, Eigen::Index count);
  // delta (the last hidden layer's dL/dz) += grad * act'(z), act' read off `act`:
  // derivative_source() of that layer.
  void add_hidden_gradient(const float* grad, Eigen::Index ld_grad, const float* act,
                           Eigen::Index rows, Eigen::Index batch, Eigen::MatrixXf& delta) const;
  // What the activation derivative of hidden layer l is computed from in the last forward: its
  // output, or for GELU its pre-activation (pre_acts_[l]).
  const float* derivative_source(int hidden_layer) const;

  std::vector<int> hidden_;
  std::vector<int> dims_;  // in, hidden..., out
  Activation act_ = Activation::kTanh;
  std::vector<Eigen::Index> w_offset_;  // start of layer l's weight in params_
  std::vector<Eigen::Index> b_offset_;  // start of layer l's bias in params_
  Eigen::VectorXf params_;
  Eigen::VectorXf grads_;
  // acts_[0] = input, acts_[l + 1] = output of layer l (after its activation when hidden).
  std::vector<Eigen::MatrixXf> acts_{1};
  // pre_acts_[l] = pre-activation z of hidden layer l (dims_[l + 1] x batch), kept by forward
  // for GELU only, whose derivative cannot be read off its output; empty for the others.
  std::vector<Eigen::MatrixXf> pre_acts_;
  // deltas_[l] = dL/d(pre-activation of hidden layer l), (dims_[l + 1] x batch).
  std::vector<Eigen::MatrixXf> deltas_;
  // wt_[l] = weight(l)^T (in x out), refreshed whenever a kernel wants the transposed layout.
  std::vector<Eigen::MatrixXf> wt_;
};

}  // namespace rlrun

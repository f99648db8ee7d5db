#pragma once
// torch.nn.LSTM (torch/nn/modules/rnn.py; batch_first false, no projection, no dropout) with
// the per-step state resets of sb3-contrib's recurrent policies
// (sb3_contrib/common/recurrent/policies.py, _process_sequence): before step t of sequence s
// whose `starts` flag is 1, the hidden and cell states of every layer are multiplied by 0.
//
// Each layer k, for inputs x_t (layer 0: the features; layer k > 0: layer k-1's h_t):
//   gates = W_ih x_t + b_ih + W_hh h_{t-1} + b_hh        (4H rows: i, f, g, o in torch's order)
//   i = sigmoid, f = sigmoid, g = tanh, o = sigmoid of their rows
//   c_t = f * c_{t-1} + i * g,   h_t = o * tanh(c_t)
// The output is the last layer's h_t. backward() is backpropagation through time over the
// sequences of the last forward(); the gradient into the initial states is dropped (they are
// rollout data, as the buffer's stored states are for sb3-contrib).
//
// Layout: sequences side by side and time-major, as torch's (seq_len, batch, features): column
// t * n + s is step t of sequence s. Parameters live in one vector (per layer: W_ih (4H x in),
// W_hh (4H x H), b_ih, b_hh, each column-major) with a same-sized gradient, so the whole LSTM is
// one optimizer block.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "rlrun/core/tensor.hpp"
#include "rlrun/nn/param_block.hpp"
#include "rlrun/rng.hpp"

namespace rlrun {

class Lstm {
 public:
  // The recurrent state of n sequences: layer k's h and c are rows [k H, (k + 1) H) of `h` and
  // `c` (num_layers * H x n), torch's (num_layers, n, H) with one sequence per column.
  struct State {
    Eigen::MatrixXf h, c;
  };

  Lstm() = default;
  // Throws std::invalid_argument for non-positive sizes. Parameters start at zero.
  Lstm(int input_size, int hidden_size, int num_layers);

  int input_size() const { return input_size_; }
  int hidden_size() const { return hidden_; }
  int num_layers() const { return layers_; }
  // Floats of one sequence's State (h and c of every layer).
  int state_size() const { return 2 * layers_ * hidden_; }
  Eigen::Index num_params() const { return params_.size(); }
  State zero_state(Eigen::Index n) const;

  // torch's LSTM.reset_parameters: every weight and bias ~ U(-1/sqrt(H), 1/sqrt(H)), layer by
  // layer in the order W_ih, W_hh, b_ih, b_hh.
  void init_torch_default(Rng& rng);

  // Runs steps = x.cols() / n steps of n sequences (x: input_size x steps * n, time-major;
  // `starts`: steps * n flags, 1 = zero the state before that step). `state` holds the initial
  // states and receives the final ones. Returns the last layer's outputs (H x steps * n), valid
  // until the next forward(), which also keeps what backward() needs.
  const Eigen::MatrixXf& forward(const Eigen::Ref<const Eigen::MatrixXf>& x,
                                 const Eigen::Ref<const Eigen::RowVectorXf>& starts, Eigen::Index n,
                                 State& state);
  // dL/d(outputs) of the last forward (H x steps * n) -> adds every parameter's gradient and,
  // if grad_x is given, writes dL/dx (input_size x steps * n).
  void backward(const Eigen::Ref<const Eigen::MatrixXf>& grad_out, Eigen::MatrixXf* grad_x);

  ParamBlock block() { return {params_.data(), grads_.data(), params_.size()}; }
  void zero_grad() { grads_.setZero(); }
  Eigen::VectorXf& params() { return params_; }
  const Eigen::VectorXf& params() const { return params_; }
  const Eigen::VectorXf& grads() const { return grads_; }

  // Layer k's parameters, torch's shapes: W_ih (4H x in_k), W_hh (4H x H), biases 4H.
  Eigen::Map<const Eigen::MatrixXf> weight_ih(int layer) const;
  Eigen::Map<const Eigen::MatrixXf> weight_hh(int layer) const;
  Eigen::Map<const Eigen::VectorXf> bias_ih(int layer) const;
  Eigen::Map<const Eigen::VectorXf> bias_hh(int layer) const;

  // torch's state_dict names under `prefix`: <prefix>.weight_ih_l<k>, .weight_hh_l<k>,
  // .bias_ih_l<k>, .bias_hh_l<k>.
  void save(const std::string& prefix, TensorMap& out) const;
  // Throws std::runtime_error for a missing tensor or one of another shape.
  void load(const std::string& prefix, const TensorMap& in);

 private:
  struct LayerOffsets {
    Eigen::Index w_ih, w_hh, b_ih, b_hh;
    int in;
  };
  // What one layer's backward needs of its forward (each column one step of one sequence).
  struct LayerCache {
    Eigen::MatrixXf input;   // x_t (in x T n)
    Eigen::MatrixXf gates;   // i, f, g, o after their nonlinearities (4H x T n)
    Eigen::MatrixXf c_prev;  // c_{t-1} after the reset (H x T n)
    Eigen::MatrixXf h_prev;  // h_{t-1} after the reset (H x T n)
    Eigen::MatrixXf tanh_c;  // tanh(c_t) (H x T n)
    Eigen::MatrixXf output;  // h_t (H x T n)
  };
  Eigen::Map<Eigen::MatrixXf> mat(Eigen::VectorXf& v, Eigen::Index offset, int rows, int cols);
  Eigen::Map<const Eigen::MatrixXf> mat(const Eigen::VectorXf& v, Eigen::Index offset, int rows,
                                        int cols) const;
  void forward_layer(int layer, const Eigen::Ref<const Eigen::MatrixXf>& x,
                     const Eigen::Ref<const Eigen::RowVectorXf>& starts, Eigen::Index n,
                     State& state, LayerCache& cache);
  void backward_layer(int layer, const Eigen::Ref<const Eigen::MatrixXf>& grad_out,
                      Eigen::MatrixXf* grad_x);

  int input_size_ = 0, hidden_ = 0, layers_ = 0;
  std::vector<LayerOffsets> offsets_;
  Eigen::VectorXf params_, grads_;
  std::vector<LayerCache> caches_;
  Eigen::RowVectorXf starts_;  // the flags of the last forward (backward resets by them)
  Eigen::Index n_ = 0;         // sequences of the last forward
  Eigen::MatrixXf grad_gates_, grad_below_, grad_layer_;
};

}  // namespace rlrun

#pragma once
// SB3's NatureCNN features extractor (common/torch_layers.py; Mnih et al. 2015, "Human-level
// control through deep reinforcement learning"): three ReLU convolutions, 32 8x8 stride 4,
// 64 4x4 stride 2, 64 3x3 stride 1, then flatten and a ReLU linear layer to features_dim (512).
// With normalize_images, SB3's preprocess_obs divides the uint8 image by 255 first; here the
// network does it on the way in.
//
// Layout: one observation per column (in_dim x batch), the image channels-last (HWC, as
// Gymnasium's envs give it) or channels-first (CHW, as after SB3's VecTransposeImage or a
// frame stack on the first axis). SB3 transposes HWC images to CHW before its convolutions;
// here the first layer reads either layout in place (conv2d.hpp) and its weight is ordered to
// match, so no transpose runs, and save()/load() write and read torch's own tensors
// (features_extractor.cnn.0.weight of shape (32, C, 8, 8), ..., linear.0.weight with torch's
// flatten order (C, H, W) of the last convolution) — the same network SB3 would compute.
//
// Parameters: like Mlp, all weights and biases in one contiguous vector (conv 0, 2, 4 weight and
// bias, then the linear layer's) with a same-sized gradient, so optimizers, copies and Polyak
// averaging are vector operations. Weights are column-major O x K (conv2d.hpp's order of K;
// for the linear layer K = the last convolution's channels-last output).
//
// Threads: a batch is cut into parts by its size alone (nn/batch_split.hpp) and each part's
// gradient is summed into grads() in part order, so results are bit-identical for every
// thread count and on AVX2 and AVX-512 (the GEMMs are dense_kernels.hpp's).
// One forward, then its backward, as for Mlp. Not thread-safe itself.
#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

#include "rlrun/core/thread_pool.hpp"
#include "rlrun/nn/conv2d.hpp"
#include "rlrun/nn/param_block.hpp"
#include "rlrun/rng.hpp"
#include "rlrun/tensor.hpp"

namespace rlrun {

// The image a CNN reads: its size and float layout in an observation.
struct ImageInput {
  int channels = 1, height = 1, width = 1;
  bool channels_last = true;  // HWC; false: CHW
  int size() const { return channels * height * width; }
};

class NatureCnn {
 public:
  static constexpr int kConvLayers = 3;

  NatureCnn() = default;
  // Throws std::invalid_argument when the image is too small for the three convolutions (SB3's
  // NatureCNN needs at least 36x36) or a size is not positive. Parameters start at zero.
  NatureCnn(const ImageInput& input, int features_dim = 512, bool normalize_images = true);

  // The three convolutions' shapes for an image; throws std::invalid_argument when it is too
  // small or has no channel. What the constructor builds, without allocating (config checks).
  static std::array<Conv2dShape, kConvLayers> conv_shapes(const ImageInput& input);

  const ImageInput& input() const { return input_; }
  int in_dim() const { return input_.size(); }
  int features_dim() const { return features_dim_; }
  bool normalize_images() const { return normalize_images_; }
  const Conv2dShape& conv(int l) const { return conv_[l]; }
  // Floats the linear layer reads (SB3's n_flatten: 3136 for 84x84).
  int flatten_dim() const { return static_cast<int>(conv_[kConvLayers - 1].out_size()); }
  Eigen::Index multiply_adds_per_column() const;
  Eigen::Index num_params() const { return params_.size(); }

  Eigen::VectorXf& params() { return params_; }
  const Eigen::VectorXf& params() const { return params_; }
  Eigen::VectorXf& grads() { return grads_; }
  const Eigen::VectorXf& grads() const { return grads_; }
  ParamBlock block() { return {params_.data(), grads_.data(), params_.size()}; }
  void zero_grad() { grads_.setZero(); }
  // Layer l's weight (O x K, column-major) and bias in params(); l = kConvLayers is the linear
  // layer.
  const float* weight(int l) const { return params_.data() + w_offset_[l]; }
  const float* bias(int l) const { return params_.data() + b_offset_[l]; }
  const float* weight_grad(int l) const { return grads_.data() + w_offset_[l]; }
  const float* bias_grad(int l) const { return grads_.data() + b_offset_[l]; }

  // SB3 ActorCriticPolicy's ortho_init (BasePolicy.init_weights: orthogonal_ with `gain` on
  // every Conv2d and Linear weight of the extractor — sqrt(2) — and zero biases), each weight
  // drawn in torch's (O, C*kh*kw) / (out, C*H*W) layout, layers first to last.
  void init_orthogonal(Rng& rng, float gain);
  // torch's default Conv2d / Linear init (what SB3's off-policy extractors keep):
  // U(-1/sqrt(fan_in), 1/sqrt(fan_in)) for weights and biases, drawn in torch's layout.
  void init_torch_default(Rng& rng);

  // features (features_dim x batch) of the images x (in_dim x batch); keeps what backward needs.
  // The reference stays valid until the next call; no allocation while the batch size stays.
  const Eigen::MatrixXf& forward(const Eigen::Ref<const Eigen::MatrixXf>& x);
  const Eigen::MatrixXf& output() const { return features_; }
  // Adds dL/d(parameters) for dL/d(features) of the last forward to grads(). Images have no
  // gradient, so none is returned for the input.
  void backward(const Eigen::Ref<const Eigen::MatrixXf>& grad_features);

  // torch state_dict entries under `prefix` (e.g. "features_extractor"): prefix.cnn.{0,2,4}.
  // {weight,bias} and prefix.linear.0.{weight,bias}, in torch's shapes and layouts.
  void save(const std::string& prefix, TensorMap& out) const;
  // Throws std::runtime_error for a missing tensor or one of another shape.
  void load(const std::string& prefix, const TensorMap& in);

  // Batches split over the pool's threads (null: the calling thread alone); never changes a
  // result.
  void set_thread_pool(ThreadPool* pool) { pool_ = pool; }

  // For export and tests: offset in params() of torch's weight element of layer l — conv:
  // [o][c][i][j], linear: [o][q] with q torch's flatten index (c * H + y) * W + x.
  Eigen::Index conv_weight_offset(int l, int o, int c, int i, int j) const;
  Eigen::Index linear_weight_offset(int o, int q) const;

 private:
  // What one part of a batch needs of its own.
  struct Workspace {
    Eigen::VectorXf patches, grad_patches;  // im2col of one sample and its gradient
    Eigen::VectorXf grad_a, grad_b;         // dL/d(a convolution's output / input), one sample
    Eigen::MatrixXf grad_linear;            // dL/d(linear pre-activation), features x count
    Eigen::MatrixXf grad_flatten;           // dL/d(last convolution's output), flatten x count
    Eigen::VectorXf grads;                  // this part's parameter gradient
  };
  // f(torch, at) for every weight of layer l: `torch` its index in torch's row-major tensor
  // ((O, C, kh, kw) or (out, C*H*W)), `at` its offset in params().
  template <class F>
  void for_each_weight(int l, F&& f) const;
  // Fills weight l from draw(rows, cols), a matrix in torch's (O, C*kh*kw) / (out, in) shape.
  template <class Draw>
  void fill_weight(int l, Draw&& draw);
  void forward_part(Eigen::Index begin, Eigen::Index count, Workspace& w);
  void backward_part(const Eigen::Ref<const Eigen::MatrixXf>& grad_features, Eigen::Index begin,
                     Eigen::Index count, Workspace& w);

  ImageInput input_;
  int features_dim_ = 0;
  bool normalize_images_ = true;
  std::array<Conv2dShape, kConvLayers> conv_{};
  std::array<Eigen::Index, kConvLayers + 1> w_offset_{}, b_offset_{};
  Eigen::VectorXf params_, grads_;
  ThreadPool* pool_ = nullptr;
  // The last forward: its input (divided by 255 when normalizing), each convolution's output
  // (channels-last, out_size x batch) and the features.
  Eigen::MatrixXf input_cache_;
  std::array<Eigen::MatrixXf, kConvLayers> acts_;
  Eigen::MatrixXf features_;
  // Transposed weights for backward: conv 1, 2 (conv 0 needs no input gradient) and linear.
  std::array<Eigen::MatrixXf, kConvLayers + 1> weight_t_;
  std::vector<Workspace> workspaces_;  // one per part
};

}  // namespace rlrun

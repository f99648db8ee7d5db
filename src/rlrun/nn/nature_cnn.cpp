#include "rlrun/nn/nature_cnn.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "rlrun/nn/batch_split.hpp"
#include "rlrun/nn/dense_kernels.hpp"
#include "rlrun/nn/orthogonal_init.hpp"

namespace rlrun {

namespace {
// NatureCNN's convolutions: (out channels, kernel, stride) (SB3 common/torch_layers.py).
constexpr int kConvSpec[NatureCnn::kConvLayers][3] = {{32, 8, 4}, {64, 4, 2}, {64, 3, 1}};
// The smallest image side the three layers fit: 8 + 4 * (4 + 2 * (3 - 1) - 1) = 36.
constexpr int kMinSide = 36;

const Tensor& find_tensor(const TensorMap& in, const std::string& name,
                          const std::vector<int64_t>& shape) {
  const auto it = in.find(name);
  if (it == in.end()) throw std::runtime_error("model file has no tensor '" + name + "'");
  if (it->second.dtype != DType::kFloat32 || it->second.shape != shape ||
      it->second.bytes.size() != static_cast<size_t>(it->second.numel()) * sizeof(float))
    throw std::runtime_error("tensor '" + name + "' has a different shape or type than the model");
  return it->second;
}

Tensor float_tensor(std::vector<int64_t> shape) {
  Tensor t;
  t.dtype = DType::kFloat32;
  t.shape = std::move(shape);
  t.bytes.resize(static_cast<size_t>(t.numel()) * sizeof(float));
  return t;
}
}  // namespace

std::array<Conv2dShape, NatureCnn::kConvLayers> NatureCnn::conv_shapes(const ImageInput& input) {
  if (input.channels <= 0)
    throw std::invalid_argument("NatureCNN: the image must have at least one channel");
  if (input.height < kMinSide || input.width < kMinSide) {
    throw std::invalid_argument("NatureCNN needs images of at least " + std::to_string(kMinSide) +
                                "x" + std::to_string(kMinSide) +
                                " (its 8x8/4, 4x4/2 and 3x3/1 convolutions), got " +
                                std::to_string(input.height) + "x" + std::to_string(input.width));
  }
  std::array<Conv2dShape, kConvLayers> shapes{};
  Conv2dShape shape{input.channels, input.height, input.width, input.channels_last, 0, 0, 0};
  for (int l = 0; l < kConvLayers; ++l) {
    shape.out_channels = kConvSpec[l][0];
    shape.kernel = kConvSpec[l][1];
    shape.stride = kConvSpec[l][2];
    check_conv2d_shape(shape, "NatureCNN");
    shapes[l] = shape;
    // The next layer reads this one's channels-last output.
    shape = Conv2dShape{shape.out_channels, shape.out_height(), shape.out_width(), true, 0, 0, 0};
  }
  return shapes;
}

NatureCnn::NatureCnn(const ImageInput& input, int features_dim, bool normalize_images)
    : input_(input),
      features_dim_(features_dim),
      normalize_images_(normalize_images),
      conv_(conv_shapes(input)) {
  if (features_dim <= 0) throw std::invalid_argument("NatureCNN: features_dim must be positive");
  Eigen::Index offset = 0;
  for (int l = 0; l < kConvLayers; ++l) {
    w_offset_[l] = offset;
    offset += conv_[l].weight_size();
    b_offset_[l] = offset;
    offset += conv_[l].out_channels;
  }
  w_offset_[kConvLayers] = offset;
  offset += Eigen::Index{features_dim} * flatten_dim();
  b_offset_[kConvLayers] = offset;
  offset += features_dim;
  params_ = Eigen::VectorXf::Zero(offset);
  grads_ = Eigen::VectorXf::Zero(offset);
  for (int l = 1; l < kConvLayers; ++l)
    weight_t_[l].resize(conv_[l].patch_size(), conv_[l].out_channels);
  weight_t_[kConvLayers].resize(flatten_dim(), features_dim);
}

Eigen::Index NatureCnn::multiply_adds_per_column() const {
  Eigen::Index total = Eigen::Index{features_dim_} * flatten_dim();
  for (const Conv2dShape& c : conv_) total += c.multiply_adds();
  return total;
}

Eigen::Index NatureCnn::conv_weight_offset(int l, int o, int c, int i, int j) const {
  return w_offset_[l] + o + conv_[l].patch_index(c, i, j) * conv_[l].out_channels;
}

Eigen::Index NatureCnn::linear_weight_offset(int o, int q) const {
  // torch flattens the last output as (c, y, x); rlrun keeps it channels-last (y, x, c).
  const Conv2dShape& last = conv_[kConvLayers - 1];
  const int hw = last.out_height() * last.out_width();
  const int c = q / hw, pixel = q % hw;
  return w_offset_[kConvLayers] + o + (Eigen::Index{pixel} * last.out_channels + c) * features_dim_;
}

template <class F>
void NatureCnn::for_each_weight(int l, F&& f) const {
  if (l < kConvLayers) {
    const Conv2dShape& s = conv_[l];
    for (int o = 0; o < s.out_channels; ++o)
      for (int c = 0; c < s.in_channels; ++c)
        for (int i = 0; i < s.kernel; ++i)
          for (int j = 0; j < s.kernel; ++j)
            f(s.torch_index(o, c, i, j), conv_weight_offset(l, o, c, i, j));
    return;
  }
  // The linear weight is a transposition with a permutation (torch: o x (c, y, x); rlrun:
  // ((y, x), c) x o): o innermost reads rlrun's side in order and writes torch's with a stride
  // that touches the same features_dim cache lines for consecutive pixels, so the 512 x 3136
  // matrix moves at memory speed (o outermost missed the cache on every element).
  const Conv2dShape& last = conv_[kConvLayers - 1];
  const int hw = last.out_height() * last.out_width();
  for (int c = 0; c < last.out_channels; ++c)
    for (int pixel = 0; pixel < hw; ++pixel) {
      const int q = c * hw + pixel;
      const Eigen::Index at = linear_weight_offset(0, q);
      for (int o = 0; o < features_dim_; ++o) f(Eigen::Index{o} * flatten_dim() + q, at + o);
    }
}

template <class Draw>
void NatureCnn::fill_weight(int l, Draw&& draw) {
  const int rows = l < kConvLayers ? conv_[l].out_channels : features_dim_;
  const int cols = l < kConvLayers ? static_cast<int>(conv_[l].patch_size()) : flatten_dim();
  using RowMajor = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  const RowMajor m = draw(rows, cols);  // torch's layout
  for_each_weight(l, [&](Eigen::Index torch, Eigen::Index at) { params_(at) = m.data()[torch]; });
}

void NatureCnn::init_orthogonal(Rng& rng, float gain) {
  for (int l = 0; l <= kConvLayers; ++l) {
    fill_weight(l, [&](int rows, int cols) {
      Eigen::MatrixXf m(rows, cols);
      orthogonal_init(m, gain, rng);
      return m;
    });
  }
  for (int l = 0; l <= kConvLayers; ++l) {
    const Eigen::Index out = l < kConvLayers ? conv_[l].out_channels : features_dim_;
    params_.segment(b_offset_[l], out).setZero();
  }
}

void NatureCnn::init_torch_default(Rng& rng) {
  for (int l = 0; l <= kConvLayers; ++l) {
    // kaiming_uniform_(a = sqrt(5)) and the bias law both reduce to U(-1/sqrt(fan_in), ...).
    const int fan_in = l < kConvLayers ? static_cast<int>(conv_[l].patch_size()) : flatten_dim();
    const double bound = 1.0 / std::sqrt(static_cast<double>(fan_in));
    fill_weight(l, [&](int rows, int cols) {
      Eigen::MatrixXf m(rows, cols);
      for (int r = 0; r < rows; ++r)  // torch's memory order: row-major
        for (int c = 0; c < cols; ++c) m(r, c) = static_cast<float>(rng.uniform(-bound, bound));
      return m;
    });
    const Eigen::Index out = l < kConvLayers ? conv_[l].out_channels : features_dim_;
    for (Eigen::Index k = 0; k < out; ++k)
      params_(b_offset_[l] + k) = static_cast<float>(rng.uniform(-bound, bound));
  }
}

const Eigen::MatrixXf& NatureCnn::forward(const Eigen::Ref<const Eigen::MatrixXf>& x) {
  if (x.rows() != in_dim())
    throw std::invalid_argument("NatureCNN: expected " + std::to_string(in_dim()) +
                                " floats per image, got " + std::to_string(x.rows()));
  const Eigen::Index n = x.cols();
  input_cache_.resize(in_dim(), n);
  for (int l = 0; l < kConvLayers; ++l) acts_[l].resize(conv_[l].out_size(), n);
  features_.resize(features_dim_, n);
  const int parts = column_parts(n, multiply_adds_per_column());
  if (static_cast<int>(workspaces_.size()) < parts) workspaces_.resize(parts);
  run_parts(pool_, parts, [&](int k) {
    const Part part = column_part(n, parts, k);
    auto in = input_cache_.middleCols(part.begin, part.count);
    // SB3 preprocess_obs: obs.float() / 255.0 for a normalized image space.
    if (normalize_images_)
      in = x.middleCols(part.begin, part.count) / 255.0f;
    else
      in = x.middleCols(part.begin, part.count);
    forward_part(part.begin, part.count, workspaces_[k]);
  });
  return features_;
}

void NatureCnn::forward_part(Eigen::Index begin, Eigen::Index count, Workspace& w) {
  w.patches.resize(conv_[0].patch_size() * conv_[0].out_pixels());
  for (int l = 1; l < kConvLayers; ++l)
    if (conv_[l].patch_size() * conv_[l].out_pixels() > w.patches.size())
      w.patches.resize(conv_[l].patch_size() * conv_[l].out_pixels());
  for (Eigen::Index s = begin; s < begin + count; ++s) {
    const float* in = input_cache_.col(s).data();
    for (int l = 0; l < kConvLayers; ++l) {
      conv2d_forward_relu(conv_[l], weight(l), bias(l), in, w.patches.data(),
                          acts_[l].col(s).data());
      in = acts_[l].col(s).data();
    }
  }
  dense::EpilogueArgs args;
  args.c = features_.col(begin).data();
  args.ldc = features_dim_;
  args.bias = bias(kConvLayers);
  dense::gemm_rows(features_dim_, count, flatten_dim(), weight(kConvLayers), features_dim_,
                   acts_[kConvLayers - 1].col(begin).data(), 1, flatten_dim(),
                   dense::Epilogue::kBiasReLU, args);
}

void NatureCnn::backward(const Eigen::Ref<const Eigen::MatrixXf>& grad_features) {
  const Eigen::Index n = features_.cols();
  if (grad_features.rows() != features_dim_ || grad_features.cols() != n)
    throw std::invalid_argument("NatureCNN::backward: gradient shape differs from the features");
  for (int l = 1; l < kConvLayers; ++l) {
    dense::transpose(conv_[l].out_channels, conv_[l].patch_size(), weight(l), conv_[l].out_channels,
                     weight_t_[l].data(), conv_[l].patch_size());
  }
  dense::transpose(features_dim_, flatten_dim(), weight(kConvLayers), features_dim_,
                   weight_t_[kConvLayers].data(), flatten_dim());
  const int parts = column_parts(n, multiply_adds_per_column());
  run_parts(pool_, parts, [&](int k) {
    const Part part = column_part(n, parts, k);
    backward_part(grad_features, part.begin, part.count, workspaces_[k]);
  });
  // Part order, whatever thread ran which part.
  for (int k = 0; k < parts; ++k) grads_ += workspaces_[k].grads;
}

void NatureCnn::backward_part(const Eigen::Ref<const Eigen::MatrixXf>& grad_features,
                              Eigen::Index begin, Eigen::Index count, Workspace& w) {
  const int f = features_dim_, flat = flatten_dim();
  w.grads.setZero(params_.size());
  // The linear layer over the part's columns: dZ = dL/dy where the ReLU passed.
  w.grad_linear = grad_features.middleCols(begin, count);
  w.grad_linear = (features_.middleCols(begin, count).array() > 0.0f).select(w.grad_linear, 0.0f);
  dense::row_sum_add(f, count, w.grad_linear.data(), f, w.grads.data() + b_offset_[kConvLayers]);
  dense::EpilogueArgs add;
  add.c = w.grads.data() + w_offset_[kConvLayers];
  add.ldc = f;
  const float* flat_in = acts_[kConvLayers - 1].col(begin).data();
  dense::gemm_rows(f, flat, count, w.grad_linear.data(), f, flat_in, flat, 1, dense::Epilogue::kAdd,
                   add);
  w.grad_flatten.resize(flat, count);
  dense::EpilogueArgs store;
  store.c = w.grad_flatten.data();
  store.ldc = flat;
  dense::gemm_rows(flat, count, f, weight_t_[kConvLayers].data(), flat, w.grad_linear.data(), 1, f,
                   dense::Epilogue::kStore, store);
  // The convolutions, one sample at a time, last layer first.
  Eigen::Index biggest_input = 0;
  for (const Conv2dShape& c : conv_) biggest_input = std::max(biggest_input, c.in_size());
  w.grad_a.resize(biggest_input);
  w.grad_b.resize(biggest_input);
  w.grad_patches.resize(w.patches.size());
  for (Eigen::Index s = begin; s < begin + count; ++s) {
    float* grad_out = w.grad_flatten.col(s - begin).data();
    float* grad_in = w.grad_a.data();
    for (int l = kConvLayers - 1; l >= 0; --l) {
      const float* in = l > 0 ? acts_[l - 1].col(s).data() : input_cache_.col(s).data();
      conv2d_im2col(conv_[l], in, w.patches.data());
      conv2d_backward_relu(conv_[l], l > 0 ? weight_t_[l].data() : nullptr, w.patches.data(),
                           acts_[l].col(s).data(), grad_out, w.grads.data() + w_offset_[l],
                           w.grads.data() + b_offset_[l], w.grad_patches.data(),
                           l > 0 ? grad_in : nullptr);
      grad_out = grad_in;
      grad_in = grad_in == w.grad_a.data() ? w.grad_b.data() : w.grad_a.data();
    }
  }
}

void NatureCnn::save(const std::string& prefix, TensorMap& out) const {
  for (int l = 0; l < kConvLayers; ++l) {
    const Conv2dShape& s = conv_[l];
    Tensor w = float_tensor({s.out_channels, s.in_channels, s.kernel, s.kernel});
    for_each_weight(
        l, [&](Eigen::Index torch, Eigen::Index at) { w.data<float>()[torch] = params_(at); });
    Tensor b = float_tensor({s.out_channels});
    std::copy_n(bias(l), s.out_channels, b.data<float>());
    const std::string name = prefix + ".cnn." + std::to_string(2 * l);
    out[name + ".weight"] = std::move(w);
    out[name + ".bias"] = std::move(b);
  }
  Tensor w = float_tensor({features_dim_, flatten_dim()});
  for_each_weight(kConvLayers, [&](Eigen::Index torch, Eigen::Index at) {
    w.data<float>()[torch] = params_(at);
  });
  Tensor b = float_tensor({features_dim_});
  std::copy_n(bias(kConvLayers), features_dim_, b.data<float>());
  out[prefix + ".linear.0.weight"] = std::move(w);
  out[prefix + ".linear.0.bias"] = std::move(b);
}

void NatureCnn::load(const std::string& prefix, const TensorMap& in) {
  for (int l = 0; l < kConvLayers; ++l) {
    const Conv2dShape& s = conv_[l];
    const std::string name = prefix + ".cnn." + std::to_string(2 * l);
    const Tensor& w =
        find_tensor(in, name + ".weight", {s.out_channels, s.in_channels, s.kernel, s.kernel});
    const Tensor& b = find_tensor(in, name + ".bias", {s.out_channels});
    for_each_weight(
        l, [&](Eigen::Index torch, Eigen::Index at) { params_(at) = w.data<float>()[torch]; });
    std::copy_n(b.data<float>(), s.out_channels, params_.data() + b_offset_[l]);
  }
  const Tensor& w = find_tensor(in, prefix + ".linear.0.weight", {features_dim_, flatten_dim()});
  const Tensor& b = find_tensor(in, prefix + ".linear.0.bias", {features_dim_});
  for_each_weight(kConvLayers, [&](Eigen::Index torch, Eigen::Index at) {
    params_(at) = w.data<float>()[torch];
  });
  std::copy_n(b.data<float>(), features_dim_, params_.data() + b_offset_[kConvLayers]);
}

}  // namespace rlrun

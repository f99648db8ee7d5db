#include "rlrun/nn/mlp.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include "rlrun/nn/dense_kernels.hpp"
#include "rlrun/nn/orthogonal_init.hpp"

namespace rlrun {

namespace {
// Below this batch size the backward input gradient uses dot products instead of transposing W
// (measured crossover on a 64-64 layer: between 2 and 4 columns).
constexpr Eigen::Index kMinBatchForTranspose = 3;

// The fused epilogue of a hidden layer's forward product: bias + activation.
dense::Epilogue forward_epilogue(Activation act) {
  switch (act) {
    case Activation::kTanh: return dense::Epilogue::kBiasTanh;
    case Activation::kReLU: return dense::Epilogue::kBiasReLU;
    case Activation::kELU: return dense::Epilogue::kBiasELU;
    case Activation::kLeakyReLU: return dense::Epilogue::kBiasLeakyReLU;
    case Activation::kGELU: return dense::Epilogue::kBiasGELU;
  }
  throw std::logic_error("Mlp: unknown activation");
}

// The fused epilogue of the product that carries dL/d(layer output) back through a hidden
// layer's activation (its derivative read off the stored output, GELU's off the stored
// pre-activation).
dense::Epilogue backward_epilogue(Activation act) {
  switch (act) {
    case Activation::kTanh: return dense::Epilogue::kTanhGrad;
    case Activation::kReLU: return dense::Epilogue::kReLUGrad;
    case Activation::kELU: return dense::Epilogue::kELUGrad;
    case Activation::kLeakyReLU: return dense::Epilogue::kLeakyReLUGrad;
    case Activation::kGELU: return dense::Epilogue::kGELUGrad;
  }
  throw std::logic_error("Mlp: unknown activation");
}
}  // namespace

Mlp::Mlp(int in_dim, std::vector<int> hidden, int out_dim, Activation act)
    : hidden_(std::move(hidden)), act_(act) {
  dims_.reserve(hidden_.size() + 2);
  dims_.push_back(in_dim);
  for (int h : hidden_) dims_.push_back(h);
  dims_.push_back(out_dim);
  for (int d : dims_) {
    if (d <= 0)
      throw std::invalid_argument("Mlp: layer sizes must be positive, got " + std::to_string(d));
  }
  const int layers = static_cast<int>(dims_.size()) - 1;
  Eigen::Index offset = 0;
  for (int l = 0; l < layers; ++l) {
    w_offset_.push_back(offset);
    offset += static_cast<Eigen::Index>(dims_[l + 1]) * dims_[l];
    b_offset_.push_back(offset);
    offset += dims_[l + 1];
  }
  params_ = Eigen::VectorXf::Zero(offset);
  grads_ = Eigen::VectorXf::Zero(offset);
  acts_.assign(layers + 1, Eigen::MatrixXf());
  deltas_.assign(layers - 1, Eigen::MatrixXf());
  if (act_ == Activation::kGELU) pre_acts_.assign(layers - 1, Eigen::MatrixXf());
  for (int l = 0; l < layers; ++l) wt_.emplace_back(dims_[l], dims_[l + 1]);
}

Eigen::Map<Eigen::MatrixXf> Mlp::weight(int layer) {
  return {params_.data() + w_offset_[layer], dims_[layer + 1], dims_[layer]};
}
Eigen::Map<const Eigen::MatrixXf> Mlp::weight(int layer) const {
  return {params_.data() + w_offset_[layer], dims_[layer + 1], dims_[layer]};
}
Eigen::Map<Eigen::VectorXf> Mlp::bias(int layer) {
  return {params_.data() + b_offset_[layer], dims_[layer + 1]};
}
Eigen::Map<const Eigen::VectorXf> Mlp::bias(int layer) const {
  return {params_.data() + b_offset_[layer], dims_[layer + 1]};
}
Eigen::Map<Eigen::MatrixXf> Mlp::weight_grad(int layer) {
  return {grads_.data() + w_offset_[layer], dims_[layer + 1], dims_[layer]};
}
Eigen::Map<const Eigen::MatrixXf> Mlp::weight_grad(int layer) const {
  return {grads_.data() + w_offset_[layer], dims_[layer + 1], dims_[layer]};
}
Eigen::Map<Eigen::VectorXf> Mlp::bias_grad(int layer) {
  return {grads_.data() + b_offset_[layer], dims_[layer + 1]};
}
Eigen::Map<const Eigen::VectorXf> Mlp::bias_grad(int layer) const {
  return {grads_.data() + b_offset_[layer], dims_[layer + 1]};
}

void Mlp::init_orthogonal(Rng& rng, float hidden_gain, float output_gain) {
  const int layers = num_layers();
  for (int l = 0; l < layers; ++l) {
    orthogonal_init(weight(l), l + 1 < layers ? hidden_gain : output_gain, rng);
    bias(l).setZero();
  }
}

void Mlp::init_torch_default(Rng& rng) {
  for (int l = 0; l < num_layers(); ++l) {
    // kaiming_uniform_ with a = sqrt(5): gain sqrt(2 / (1 + 5)), bound gain * sqrt(3 / fan_in)
    // = 1 / sqrt(fan_in); the bias bound is 1 / sqrt(fan_in) too.
    const double bound = 1.0 / std::sqrt(static_cast<double>(dims_[l]));
    auto w = weight(l);
    for (Eigen::Index k = 0; k < w.size(); ++k) {
      w.data()[k] = static_cast<float>(rng.uniform(-bound, bound));
    }
    auto b = bias(l);
    for (Eigen::Index k = 0; k < b.size(); ++k)
      b(k) = static_cast<float>(rng.uniform(-bound, bound));
  }
}

const Eigen::MatrixXf& Mlp::forward(const Eigen::Ref<const Eigen::MatrixXf>& x) {
  return forward_with(params_.data(), x);
}

const Eigen::MatrixXf& Mlp::forward_with(const float* p,
                                         const Eigen::Ref<const Eigen::MatrixXf>& x) {
  if (x.rows() != in_dim()) {
    throw std::invalid_argument("Mlp::forward: input has " + std::to_string(x.rows()) +
                                " rows, network expects " + std::to_string(in_dim()));
  }
  const int layers = num_layers();
  const Eigen::Index batch = x.cols();
  // Kept for the first layer's weight gradient; resizes only on a new batch size. A contiguous
  // input is one block copy: Eigen copies a Ref with a run-time stride column by column, a
  // scalar loop of 3 floats per column for Pendulum (2.5 % of RLtools-PPO's profile).
  const bool stored_input = x.data() == acts_[0].data() && x.size() == acts_[0].size();
  if (!stored_input) {
    if (x.outerStride() == x.rows()) {
      acts_[0].resize(x.rows(), x.cols());
      std::copy_n(x.data(), x.size(), acts_[0].data());
    } else {
      acts_[0] = x;
    }
  }
  for (int l = 0; l < layers; ++l) {
    const Eigen::Index in = dims_[l];
    const Eigen::Index out = dims_[l + 1];
    Eigen::MatrixXf& z = acts_[l + 1];
    z.resize(out, batch);
    const dense::Epilogue epilogue =
        l + 1 < layers ? forward_epilogue(act_) : dense::Epilogue::kBias;
    const float* w = p + w_offset_[l];
    dense::EpilogueArgs args{.c = z.data(), .ldc = out, .bias = p + b_offset_[l]};
    if (epilogue == dense::Epilogue::kBiasGELU) {
      pre_acts_[l].resize(out, batch);
      args.pre = pre_acts_[l].data();
    }
    if (out >= dense::kLogicalLanes) {
      dense::gemm_rows(out, batch, in, w, out, acts_[l].data(), 1, in, epilogue, args);
    } else {
      // Few output units (a value or small action head): dot products over the input features.
      dense::transpose(out, in, w, out, wt_[l].data(), in);
      dense::gemm_dot(out, batch, in, wt_[l].data(), in, acts_[l].data(), in, epilogue, args);
    }
  }
  return acts_.back();
}

void Mlp::backward(const Eigen::Ref<const Eigen::MatrixXf>& grad_output,
                   Eigen::MatrixXf* grad_input, const Eigen::MatrixXf* grad_last_hidden) {
  if (grad_input != nullptr) grad_input->resize(in_dim(), acts_[0].cols());
  if (grad_last_hidden != nullptr && (grad_last_hidden->rows() != last_hidden().rows() ||
                                      grad_last_hidden->cols() != last_hidden().cols()))
    throw std::invalid_argument("Mlp::backward: grad_last_hidden does not match last_hidden()");
  backward_pass(params_.data(), grad_output, true, grad_input ? grad_input->data() : nullptr, 0,
                grad_last_hidden ? grad_last_hidden->data() : nullptr,
                grad_last_hidden ? grad_last_hidden->rows() : 0);
}

void Mlp::backward_input(const Eigen::Ref<const Eigen::MatrixXf>& grad_output,
                         Eigen::MatrixXf& grad_input, int first_input_row) {
  if (first_input_row < 0 || first_input_row >= in_dim()) {
    throw std::invalid_argument("Mlp::backward_input: first_input_row " +
                                std::to_string(first_input_row) + " is not below in_dim " +
                                std::to_string(in_dim()));
  }
  grad_input.resize(in_dim() - first_input_row, acts_[0].cols());
  backward_pass(params_.data(), grad_output, false, grad_input.data(), first_input_row);
}

bool Mlp::uses_transposed_weight(Eigen::Index rows, Eigen::Index batch) {
  return rows >= dense::kLogicalLanes && batch >= kMinBatchForTranspose;
}

void Mlp::transpose_weight_rows(const float* p, int l, Eigen::Index begin, Eigen::Index count) {
  // W is out x in (column-major): its columns [begin, begin + count) are W^T's rows.
  const Eigen::Index out = dims_[l + 1];
  dense::transpose(out, count, p + w_offset_[l] + begin * out, out, wt_[l].data() + begin,
                   dims_[l]);
}

void Mlp::backward_pass(const float* p, const Eigen::Ref<const Eigen::MatrixXf>& grad_output,
                        bool param_grads, float* grad_input, int first_input_row,
                        const float* grad_hidden, Eigen::Index ld_grad_hidden,
                        const Mlp* transposed_by) {
  const int layers = num_layers();
  const Eigen::Index batch = acts_[0].cols();
  if (grad_output.rows() != out_dim() || grad_output.cols() != batch) {
    throw std::invalid_argument("Mlp::backward: grad_output is " +
                                std::to_string(grad_output.rows()) + "x" +
                                std::to_string(grad_output.cols()) + ", last forward gave " +
                                std::to_string(out_dim()) + "x" + std::to_string(batch));
  }
  const int lanes = dense::kLogicalLanes;  // shapes alone pick the kernel (same bits everywhere)
  for (int l = layers - 1; l >= 0; --l) {
    const Eigen::Index in = dims_[l];
    const Eigen::Index out = dims_[l + 1];
    // dL/dz of layer l: the caller's gradient for the linear head, else our buffer.
    const float* delta = l + 1 == layers ? grad_output.data() : deltas_[l].data();
    const Eigen::Index ld_delta = l + 1 == layers ? grad_output.outerStride() : out;
    const float* input = acts_[l].data();

    if (param_grads) {
      // dW += delta input^T, vectorised over whichever of out / in is wider.
      if (out >= lanes || out >= in) {
        dense::gemm_rows(out, in, batch, delta, ld_delta, input, in, 1, dense::Epilogue::kAdd,
                         {.c = weight_grad(l).data(), .ldc = out});
      } else {
        dense::gemm_rows(in, out, batch, input, in, delta, ld_delta, 1,
                         dense::Epilogue::kAddTransposed, {.c = weight_grad(l).data(), .ldc = out});
      }
      // db += delta 1, summed over the batch in order.
      dense::row_sum_add(out, batch, delta, ld_delta, bias_grad(l).data());
    }

    // dL/d(input) = W^T delta, times act'(input) when the input is a hidden activation:
    // e.g. tanh' = 1 - a^2, relu' = [a > 0], read off the stored activation (dense_kernels.hpp);
    // gelu' off the stored pre-activation.
    // For the network's input only rows [first, in) are wanted: the columns [first, in) of W.
    Eigen::Index first = 0;
    dense::EpilogueArgs args;
    dense::Epilogue epilogue = dense::Epilogue::kStore;
    if (l > 0) {
      deltas_[l - 1].resize(in, batch);
      args.c = deltas_[l - 1].data();
      epilogue = backward_epilogue(act_);
      args.act = derivative_source(l - 1);
      args.ld_act = in;
    } else if (grad_input != nullptr) {
      first = first_input_row;
      args.c = grad_input;
    } else {
      continue;
    }
    const Eigen::Index rows = in - first;
    args.ldc = rows;
    // Large batches: transpose W once (in x out, cheap next to the product) and vectorise over
    // the rows of the result. Small batches (environment stepping) or narrow inputs: dot
    // products against W's columns, which needs no transpose.
    const float* w = p + w_offset_[l];
    if (uses_transposed_weight(rows, batch)) {
      if (transposed_by == nullptr) transpose_weight_rows(p, l, 0, in);
      const float* wt = (transposed_by ? transposed_by : this)->wt_[l].data();
      dense::gemm_rows(rows, batch, out, wt + first, in, delta, 1, ld_delta, epilogue, args);
    } else {
      dense::gemm_dot(rows, batch, out, w + first * out, out, delta, ld_delta, epilogue, args);
    }
    if (grad_hidden != nullptr && l + 1 == layers && l > 0)
      add_hidden_gradient(grad_hidden, ld_grad_hidden, derivative_source(l - 1), in, batch,
                          deltas_[l - 1]);
  }
}

const float* Mlp::derivative_source(int hidden_layer) const {
  return act_ == Activation::kGELU ? pre_acts_[hidden_layer].data()
                                   : acts_[hidden_layer + 1].data();
}

void Mlp::add_hidden_gradient(const float* grad, Eigen::Index ld_grad, const float* act,
                              Eigen::Index rows, Eigen::Index batch, Eigen::MatrixXf& delta) const {
  // delta = (W^T delta_next) * act'(z) already; (W^T delta_next + g) * act'(z) adds g * act'(z),
  // with act' read off the activation as the backward epilogues do (GELU: off z itself).
  const Eigen::Map<const Eigen::MatrixXf, 0, Eigen::OuterStride<>> g(grad, rows, batch,
                                                                     Eigen::OuterStride<>(ld_grad));
  const Eigen::Map<const Eigen::MatrixXf> a(act, rows, batch);
  switch (act_) {
    case Activation::kTanh: delta.array() += g.array() * (1.0f - a.array().square()); break;
    case Activation::kReLU: delta.array() += (a.array() > 0.0f).select(g.array(), 0.0f); break;
    case Activation::kELU:  // d/dz (exp(z) - 1) = exp(z) = a + 1 below zero
      delta.array() += (a.array() > 0.0f).select(g.array(), g.array() * (a.array() + 1.0f));
      break;
    case Activation::kLeakyReLU:
      delta.array() += (a.array() > 0.0f).select(g.array(), g.array() * kLeakyReLUSlope);
      break;
    case Activation::kGELU:  // gelu'(z) = Phi(z) + z phi(z), Phi(z) = erfc(-z / sqrt(2)) / 2
      delta.array() += g.array() * a.array().unaryExpr([](float z) {
        constexpr float kInvSqrt2 = 0.70710678118654752f, kInvSqrt2Pi = 0.39894228040143268f;
        return 0.5f * std::erfc(-z * kInvSqrt2) + z * kInvSqrt2Pi * std::exp(-0.5f * z * z);
      });
      break;
  }
}

}  // namespace rlrun

#include "rlrun/nn/lstm.hpp"

#include <cmath>
#include <stdexcept>

namespace rlrun {

namespace {
float sigmoid(float x) { return 1.0f / (1.0f + std::exp(-x)); }
}  // namespace

Lstm::Lstm(int input_size, int hidden_size, int num_layers)
    : input_size_(input_size), hidden_(hidden_size), layers_(num_layers) {
  if (input_size < 1 || hidden_size < 1 || num_layers < 1)
    throw std::invalid_argument("Lstm: sizes must be positive");
  Eigen::Index offset = 0;
  const Eigen::Index gates = 4 * Eigen::Index{hidden_size};
  for (int k = 0; k < num_layers; ++k) {
    LayerOffsets o;
    o.in = k == 0 ? input_size : hidden_size;
    o.w_ih = offset;
    offset += gates * o.in;
    o.w_hh = offset;
    offset += gates * hidden_size;
    o.b_ih = offset;
    offset += gates;
    o.b_hh = offset;
    offset += gates;
    offsets_.push_back(o);
  }
  params_ = Eigen::VectorXf::Zero(offset);
  grads_ = Eigen::VectorXf::Zero(offset);
  caches_.resize(static_cast<size_t>(num_layers));
}

Lstm::State Lstm::zero_state(Eigen::Index n) const {
  const Eigen::Index rows = Eigen::Index{layers_} * hidden_;
  return {Eigen::MatrixXf::Zero(rows, n), Eigen::MatrixXf::Zero(rows, n)};
}

void Lstm::init_torch_default(Rng& rng) {
  // torch RNNBase.reset_parameters: init.uniform_(weight, -stdv, stdv), stdv = 1/sqrt(H), for
  // every parameter in _flat_weights order (per layer: w_ih, w_hh, b_ih, b_hh) — the layout of
  // params_ itself.
  const double bound = 1.0 / std::sqrt(static_cast<double>(hidden_));
  for (Eigen::Index k = 0; k < params_.size(); ++k)
    params_(k) = static_cast<float>(rng.uniform(-bound, bound));
}

Eigen::Map<Eigen::MatrixXf> Lstm::mat(Eigen::VectorXf& v, Eigen::Index offset, int rows, int cols) {
  return {v.data() + offset, rows, cols};
}
Eigen::Map<const Eigen::MatrixXf> Lstm::mat(const Eigen::VectorXf& v, Eigen::Index offset, int rows,
                                            int cols) const {
  return {v.data() + offset, rows, cols};
}

Eigen::Map<const Eigen::MatrixXf> Lstm::weight_ih(int layer) const {
  const LayerOffsets& o = offsets_[static_cast<size_t>(layer)];
  return mat(params_, o.w_ih, 4 * hidden_, o.in);
}
Eigen::Map<const Eigen::MatrixXf> Lstm::weight_hh(int layer) const {
  return mat(params_, offsets_[static_cast<size_t>(layer)].w_hh, 4 * hidden_, hidden_);
}
Eigen::Map<const Eigen::VectorXf> Lstm::bias_ih(int layer) const {
  return {params_.data() + offsets_[static_cast<size_t>(layer)].b_ih, 4 * hidden_};
}
Eigen::Map<const Eigen::VectorXf> Lstm::bias_hh(int layer) const {
  return {params_.data() + offsets_[static_cast<size_t>(layer)].b_hh, 4 * hidden_};
}

const Eigen::MatrixXf& Lstm::forward(const Eigen::Ref<const Eigen::MatrixXf>& x,
                                     const Eigen::Ref<const Eigen::RowVectorXf>& starts,
                                     Eigen::Index n, State& state) {
  if (x.rows() != input_size_ || n < 1 || x.cols() % n != 0 || starts.size() != x.cols())
    throw std::invalid_argument("Lstm::forward: inputs of another shape");
  const Eigen::Index rows = Eigen::Index{layers_} * hidden_;
  if (state.h.rows() != rows || state.h.cols() != n || state.c.rows() != rows ||
      state.c.cols() != n)
    throw std::invalid_argument("Lstm::forward: a state of another shape");
  starts_ = starts;
  n_ = n;
  for (int k = 0; k < layers_; ++k)
    forward_layer(k, k == 0 ? x : Eigen::Ref<const Eigen::MatrixXf>(caches_[k - 1].output), starts,
                  n, state, caches_[static_cast<size_t>(k)]);
  return caches_.back().output;
}

void Lstm::forward_layer(int layer, const Eigen::Ref<const Eigen::MatrixXf>& x,
                         const Eigen::Ref<const Eigen::RowVectorXf>& starts, Eigen::Index n,
                         State& state, LayerCache& cache) {
  const int H = hidden_;
  const Eigen::Index columns = x.cols();
  cache.input = x;
  // The input part of every step at once: W_ih x + b_ih + b_hh.
  cache.gates.noalias() = weight_ih(layer) * x;
  cache.gates.colwise() += bias_ih(layer) + bias_hh(layer);
  cache.c_prev.resize(H, columns);
  cache.h_prev.resize(H, columns);
  cache.tanh_c.resize(H, columns);
  cache.output.resize(H, columns);
  auto h = state.h.middleRows(Eigen::Index{layer} * H, H);
  auto c = state.c.middleRows(Eigen::Index{layer} * H, H);
  const Eigen::Map<const Eigen::MatrixXf> w_hh = weight_hh(layer);
  for (Eigen::Index t = 0; t * n < columns; ++t) {
    const Eigen::Index first = t * n;
    for (Eigen::Index s = 0; s < n; ++s) {
      if (starts(first + s) != 0.0f) {
        h.col(s).setZero();
        c.col(s).setZero();
      }
    }
    cache.h_prev.middleCols(first, n) = h;
    cache.c_prev.middleCols(first, n) = c;
    auto gates = cache.gates.middleCols(first, n);
    gates.noalias() += w_hh * h;
    for (Eigen::Index s = 0; s < n; ++s) {
      for (int j = 0; j < H; ++j) {
        const float i = sigmoid(gates(j, s));
        const float f = sigmoid(gates(H + j, s));
        const float g = std::tanh(gates(2 * H + j, s));
        const float o = sigmoid(gates(3 * H + j, s));
        gates(j, s) = i;
        gates(H + j, s) = f;
        gates(2 * H + j, s) = g;
        gates(3 * H + j, s) = o;
        const float c_new = f * c(j, s) + i * g;
        const float tanh_c = std::tanh(c_new);
        c(j, s) = c_new;
        h(j, s) = o * tanh_c;
        cache.tanh_c(j, first + s) = tanh_c;
      }
    }
    cache.output.middleCols(first, n) = h;
  }
}

void Lstm::backward(const Eigen::Ref<const Eigen::MatrixXf>& grad_out, Eigen::MatrixXf* grad_x) {
  if (n_ == 0 || grad_out.rows() != hidden_ || grad_out.cols() != caches_.back().output.cols())
    throw std::invalid_argument("Lstm::backward: gradients of another shape than the outputs");
  grad_layer_ = grad_out;
  for (int k = layers_ - 1; k >= 0; --k) {
    // The layer below gets dL/d(its outputs) in grad_below_; layer 0 gives dL/dx.
    Eigen::MatrixXf* below = k > 0 ? &grad_below_ : grad_x;
    backward_layer(k, grad_layer_, below);
    if (k > 0) grad_layer_.swap(grad_below_);
  }
}

void Lstm::backward_layer(int layer, const Eigen::Ref<const Eigen::MatrixXf>& grad_out,
                          Eigen::MatrixXf* grad_x) {
  const LayerCache& cache = caches_[static_cast<size_t>(layer)];
  const LayerOffsets& o = offsets_[static_cast<size_t>(layer)];
  const int H = hidden_;
  const Eigen::Index n = n_, columns = grad_out.cols();
  const Eigen::Map<const Eigen::MatrixXf> w_hh = weight_hh(layer);
  grad_gates_.resize(4 * H, columns);
  // dL/dh_{t-1} and dL/dc_{t-1} carried back from step t (zero past the last step).
  Eigen::MatrixXf dh_next = Eigen::MatrixXf::Zero(H, n), dc_next = Eigen::MatrixXf::Zero(H, n);
  for (Eigen::Index t = columns / n - 1; t >= 0; --t) {
    const Eigen::Index first = t * n;
    auto da = grad_gates_.middleCols(first, n);
    for (Eigen::Index s = 0; s < n; ++s) {
      const Eigen::Index col = first + s;
      for (int j = 0; j < H; ++j) {
        const float i = cache.gates(j, col), f = cache.gates(H + j, col);
        const float g = cache.gates(2 * H + j, col), og = cache.gates(3 * H + j, col);
        const float tanh_c = cache.tanh_c(j, col);
        const float dh = grad_out(j, col) + dh_next(j, s);
        const float dc = dh * og * (1.0f - tanh_c * tanh_c) + dc_next(j, s);
        da(j, s) = dc * g * i * (1.0f - i);
        da(H + j, s) = dc * cache.c_prev(j, col) * f * (1.0f - f);
        da(2 * H + j, s) = dc * i * (1.0f - g * g);
        da(3 * H + j, s) = dh * tanh_c * og * (1.0f - og);
        dc_next(j, s) = dc * f;
      }
    }
    dh_next.noalias() = w_hh.transpose() * da;
    // A reset multiplied the carried state by 0: nothing flows into the step before.
    for (Eigen::Index s = 0; s < n; ++s) {
      if (starts_(first + s) != 0.0f) {
        dh_next.col(s).setZero();
        dc_next.col(s).setZero();
      }
    }
  }
  mat(grads_, o.w_ih, 4 * H, o.in).noalias() += grad_gates_ * cache.input.transpose();
  mat(grads_, o.w_hh, 4 * H, H).noalias() += grad_gates_ * cache.h_prev.transpose();
  const Eigen::VectorXf bias_grad = grad_gates_.rowwise().sum();
  grads_.segment(o.b_ih, 4 * H) += bias_grad;
  grads_.segment(o.b_hh, 4 * H) += bias_grad;
  if (grad_x) grad_x->noalias() = mat(params_, o.w_ih, 4 * H, o.in).transpose() * grad_gates_;
}

void Lstm::save(const std::string& prefix, TensorMap& out) const {
  for (int k = 0; k < layers_; ++k) {
    const std::string l = "_l" + std::to_string(k);
    out[prefix + ".weight_ih" + l] = to_tensor(Eigen::MatrixXf(weight_ih(k)));
    out[prefix + ".weight_hh" + l] = to_tensor(Eigen::MatrixXf(weight_hh(k)));
    out[prefix + ".bias_ih" + l] = to_tensor(Eigen::VectorXf(bias_ih(k)));
    out[prefix + ".bias_hh" + l] = to_tensor(Eigen::VectorXf(bias_hh(k)));
  }
}

void Lstm::load(const std::string& prefix, const TensorMap& in) {
  for (int k = 0; k < layers_; ++k) {
    const LayerOffsets& o = offsets_[static_cast<size_t>(k)];
    const std::string l = "_l" + std::to_string(k);
    from_tensor(in, prefix + ".weight_ih" + l, mat(params_, o.w_ih, 4 * hidden_, o.in));
    from_tensor(in, prefix + ".weight_hh" + l, mat(params_, o.w_hh, 4 * hidden_, hidden_));
    Eigen::Map<Eigen::VectorXf> b_ih(params_.data() + o.b_ih, 4 * hidden_);
    Eigen::Map<Eigen::VectorXf> b_hh(params_.data() + o.b_hh, 4 * hidden_);
    from_tensor(in, prefix + ".bias_ih" + l, b_ih);
    from_tensor(in, prefix + ".bias_hh" + l, b_hh);
  }
}

}  // namespace rlrun

#include "rlrun/nn/split_mlp.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>

#include "rlrun/nn/batch_split.hpp"

namespace rlrun {

SplitMlp::SplitMlp(int in_dim, std::vector<int> hidden, int out_dim, Activation act,
                   ThreadPool* pool)
    : net_(in_dim, std::move(hidden), out_dim, act), pool_(pool) {}

SplitMlp::SplitMlp(Mlp net, ThreadPool* pool) : net_(std::move(net)), pool_(pool) {}

SplitMlp& SplitMlp::operator=(const SplitMlp& other) {
  if (this == &other) return *this;
  net_ = other.net_;
  pool_ = other.pool_;
  replica_.reset();
  parts_ = 1;
  return *this;
}

Mlp& SplitMlp::replica() {
  if (!replica_) {
    replica_.emplace(net_.in_dim(), net_.hidden(), net_.out_dim(), net_.activation());
    replica_->params_.resize(0);  // it reads net_'s
  }
  return *replica_;
}

const Eigen::MatrixXf& SplitMlp::forward(const Eigen::Ref<const Eigen::MatrixXf>& x) {
  const Eigen::Index n = x.cols();
  parts_ = column_parts(n, net_.multiply_adds_per_column());
  if (parts_ == 1) return net_.forward(x);
  Mlp& replica = this->replica();
  const float* p = net_.params_.data();
  output_.resize(net_.out_dim(), n);
  run_parts(pool_, 2, [&](int k) {
    const Part cols = column_part(n, 2, k);
    Mlp& half = k == 0 ? net_ : replica;
    output_.middleCols(cols.begin, cols.count) =
        half.forward_with(p, x.middleCols(cols.begin, cols.count));
  });
  return output_;
}

void SplitMlp::backward(const Eigen::Ref<const Eigen::MatrixXf>& grad_output) {
  backward_halves(grad_output, false);
}

void SplitMlp::zero_grad_and_backward(const Eigen::Ref<const Eigen::MatrixXf>& grad_output,
                                      const Eigen::MatrixXf* grad_last_hidden) {
  backward_halves(grad_output, true, grad_last_hidden);
}

const Eigen::MatrixXf& SplitMlp::last_hidden() {
  if (parts_ == 1) return net_.last_hidden();
  const Mlp& replica = *replica_;
  const Eigen::Index first = net_.last_hidden().cols();
  last_hidden_.resize(net_.last_hidden().rows(), first + replica.last_hidden().cols());
  last_hidden_.leftCols(first) = net_.last_hidden();
  last_hidden_.rightCols(replica.last_hidden().cols()) = replica.last_hidden();
  return last_hidden_;
}

void SplitMlp::backward_halves(const Eigen::Ref<const Eigen::MatrixXf>& grad_output,
                               bool zero_first, const Eigen::MatrixXf* grad_last_hidden) {
  if (parts_ == 1) {
    if (zero_first) net_.zero_grad();
    net_.backward(grad_output, nullptr, grad_last_hidden);
    return;
  }
  if (grad_last_hidden != nullptr && grad_last_hidden->cols() != grad_output.cols())
    throw std::invalid_argument("SplitMlp::backward: grad_last_hidden has the wrong batch");
  const Eigen::Index n = grad_output.cols();
  Mlp& replica = *replica_;
  const float* p = net_.params_.data();
  transpose_for_halves(n, false);
  run_parts(pool_, 2, [&](int k) {
    const Part cols = column_part(n, 2, k);
    Mlp& half = k == 0 ? net_ : replica;
    if (k == 1 || zero_first) half.zero_grad();  // the replica holds the second half's alone
    const float* grad_hidden =
        grad_last_hidden ? grad_last_hidden->data() + cols.begin * grad_last_hidden->rows()
                         : nullptr;
    half.backward_pass(p, grad_output.middleCols(cols.begin, cols.count), true, nullptr, 0,
                       grad_hidden, grad_last_hidden ? grad_last_hidden->rows() : 0, &net_);
  });
  // grads += the second half's gradient, each core adding its part of the parameter vector.
  run_parts(pool_, 2, [&](int k) {
    const Part params = param_part(net_.num_params(), k);
    net_.grads_.segment(params.begin, params.count) +=
        replica.grads_.segment(params.begin, params.count);
  });
}

void SplitMlp::backward_input(const Eigen::Ref<const Eigen::MatrixXf>& grad_output,
                              Eigen::MatrixXf& grad_input, int first_input_row) {
  if (parts_ == 1) {
    net_.backward_input(grad_output, grad_input, first_input_row);
    return;
  }
  if (first_input_row < 0 || first_input_row >= net_.in_dim())
    throw std::invalid_argument("SplitMlp::backward_input: first_input_row " +
                                std::to_string(first_input_row) + " is not below in_dim " +
                                std::to_string(net_.in_dim()));
  const Eigen::Index n = grad_output.cols();
  Mlp& replica = *replica_;
  const float* p = net_.params_.data();
  grad_input.resize(net_.in_dim() - first_input_row, n);
  transpose_for_halves(n, true, first_input_row);
  run_parts(pool_, 2, [&](int k) {
    const Part cols = column_part(n, 2, k);
    Mlp& half = k == 0 ? net_ : replica;
    half.backward_pass(p, grad_output.middleCols(cols.begin, cols.count), false,
                       grad_input.data() + cols.begin * grad_input.rows(), first_input_row,
                       nullptr, 0, &net_);
  });
}

void SplitMlp::transpose_for_halves(Eigen::Index n, bool input_gradient, int first_input_row) {
  // A layer is transposed when either half's backward_pass would use W^T (the larger half's
  // batch decides); each half still chooses its kernel from its own batch.
  const Eigen::Index batch = std::max(column_part(n, 2, 0).count, column_part(n, 2, 1).count);
  const float* p = net_.params_.data();
  run_parts(pool_, 2, [&](int k) {
    for (int l = input_gradient ? 0 : 1; l < net_.num_layers(); ++l) {
      const Eigen::Index in = net_.dims_[l];
      if (!Mlp::uses_transposed_weight(l == 0 ? in - first_input_row : in, batch)) continue;
      const Part rows = param_part(in, k);  // whole cache lines of each W^T column per core
      net_.transpose_weight_rows(p, l, rows.begin, rows.count);
    }
  });
}

}  // namespace rlrun
